local sun = vdg.group{name = 'sun'}
local orbit = vdg.group{name = 'orbit', parent = sun}
local earth = vdg.group{name = 'earth', parent = orbit, translation = {10, 0, 0}, scale = 0.5}
vdg.change(orbit, 'rotation', vdg.quat.axis_angle({0, 1, 0}, 360), 0, 365)
vdg.set(earth, 'visible', false, 400)
