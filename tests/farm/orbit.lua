-- A 40-frame camera orbit around the spot model (examples/spot, five key deformations): the farm
-- test's shot (tests/farm/farm_test.sh), small so that a 4-task job array renders it in seconds.
-- Every frame shows another side of the cow, so a frame rendered from the wrong camera or another
-- frame's state differs from the local render.
--
--   vdg run tests/farm/orbit.lua --root . -o out
-- (--root: the script loads examples/spot, so it may read below the repository root)

local spot = vdg.load("../../examples/spot/spot.vdg.json")
local cow = vdg.node{name = "cow", object = spot}

-- The camera rides on a rig that turns once about the cow's vertical axis over the 40 frames.
local rig = vdg.group{name = "rig"}
vdg.camera{name = "camera", parent = rig, translation = {0, 1.2, 3.5}, look_at = cow, fov = 40}
vdg.change(rig, "rotation", vdg.quat.axis_angle({0, 1, 0}, 360), 0, 40)

vdg.render{frames = "0-39", size = {96, 96}, out = "orbit", samples = 4}
