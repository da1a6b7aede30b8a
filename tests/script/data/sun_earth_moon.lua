-- Parent 4.7's sun-earth-moon hierarchy as a script (groups only: the test reads the numbers).
-- One day per frame: the earth circles the sun in 365 frames, the moon the earth in 28.
local sun = vdg.group{name = "sun"}
local earth_orbit = vdg.group{name = "earth_orbit", parent = sun}
local earth = vdg.group{name = "earth", parent = earth_orbit, translation = {10, 0, 0}}
local moon_orbit = vdg.group{name = "moon_orbit", parent = earth}
local moon = vdg.group{name = "moon", parent = moon_orbit, translation = {2, 0, 0}}
-- Keys a quarter turn apart: slerp takes the shorter arc between neighbouring keys.
local keys = {}
for quarter = 0, 4 do keys[#keys + 1] = {365 * quarter / 4, vdg.quat.axis_angle({0, 1, 0}, 90 * quarter)} end
vdg.track(earth_orbit, "rotation", keys, "slerp")
local turn = vdg.quat.axis_angle({0, 1, 0}, 360 / 28)
for day = 1, 28 do
  vdg.change(moon_orbit, "rotation", turn, day - 1, day)
end
local cam = vdg.camera{name = "cam", translation = {0, 30, 30}, look_at = sun}
vdg.render{frames = "0-364", size = {320, 180}, out = "year"}
print(string.format("earth orbit %.1f, moon orbit %.1f", 10, 2))
