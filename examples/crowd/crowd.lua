-- A crowd: 64 instances of one view-dependent model (examples/spot, five key deformations), each
-- turned its own way. Every member is blended for the direction from its own centre to the camera,
-- in its own frame (Rademacher 99, section 1: characters "replicated many times from different
-- angles"), so the camera sees front keys on some cows and side or back keys on others in the same
-- frame, each as the model sheet drew that view.
--
--   vdg run examples/crowd/crowd.lua --root examples -o out
-- (--root: the script loads ../spot, so it may read below examples/)

local spot = vdg.load("../spot/spot.vdg.json")
local kRows, kColumns, kSpacing = 8, 8, 2.4
local kGoldenAngle = 137.50776  -- degrees: headings that never line up

local herd = vdg.group{name = "herd"}
local cows = {}
for i = 0, kRows * kColumns - 1 do
  local row, column = i // kColumns, i % kColumns
  cows[#cows + 1] = vdg.node{
    name = "cow" .. i, object = spot, parent = herd,
    translation = {(column - (kColumns - 1) / 2) * kSpacing, 0, (row - (kRows - 1) / 2) * kSpacing},
    rotation = vdg.quat.axis_angle({0, 1, 0}, (i * kGoldenAngle) % 360),
    placement = {translation = {0, 0.74, 0}},  -- hooves on the ground
  }
end

-- Every cow turns a little while the camera flies over: FOR EACH with its own amount.
vdg.for_each(cows, function(cow, i)
  vdg.change(cow, "rotation", vdg.quat.axis_angle({0, 1, 0}, 20 + (i % 5) * 10), 0, 47, "sine")
end)

vdg.camera{name = "camera", look_at = herd, fov = 40,
           path = {points = {{-16, 7, 14}, {-4, 9, 19}, {8, 8, 18}, {18, 7, 11}},
                   ease = vdg.ease.make("sinusoidal", 0.2, 0.8), start = 0, ["end"] = 47}}
vdg.render{frames = "0-47", size = {640, 360}, out = "crowd"}
