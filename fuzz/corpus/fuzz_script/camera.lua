local target = vdg.group{name = 'target'}
local cam = vdg.camera{name = 'cam', fov = 35, look_at = target,
  path = {points = {{0, 0, 10}, {10, 2, 0}, {0, 0, -10}}, interpolation = 'catmull-rom',
          ease = vdg.ease.make('sine'), start = 1, ['end'] = 48, tilt = {{1, 0}, {48, 10}}}}
vdg.use_camera(cam)
local c = vdg.curve{points = {{0, 0}, {1, 1}, {2, 0}}, interpolation = 'natural-cubic'}
print(c:eval(0.5)[1], c:length(), c:at_length(1)[2], c:range())
print(vdg.quat.slerp(vdg.quat.identity(), vdg.quat.axis_angle({1, 0, 0}, 90), 0.5):rotate({0, 1, 0})[3])
print(vdg.ease.sine(0.25), vdg.ease.sinusoidal(0.5, 0.2, 0.8), vdg.ease.parabolic(0.5, 0.2, 0.8))
