-- The cubist Spot (spot-cubist.vdg.json, per-part key sets; docs/weights.md) beside the plain one,
-- while the camera circles them. The plain cow (left) blends its five keys for the camera's view
-- everywhere; the cubist cow (right) does so for its body only: its head is a part with a fixed
-- driving view, so it keeps the front drawing (ears flared, horns spread) from every side.
--
--   vdg run examples/spot/cubist.lua --root examples -o out
local plain = vdg.load("spot.vdg.json")
local cubist = vdg.load("spot-cubist.vdg.json")
local pair = vdg.group{name = "pair"}
vdg.node{name = "plain", object = plain, parent = pair, translation = {-1.3, 0, 0}}
vdg.node{name = "cubist", object = cubist, parent = pair, translation = {1.3, 0, 0}}
vdg.camera{name = "camera", look_at = pair, fov = 35,
           path = {points = {{0, 1.5, -7}, {7, 1.5, 0}, {0, 1.5, 7}, {-7, 1.5, 0}, {0, 1.5, -7}}, start = 0, ["end"] = 47}}
vdg.render{frames = "0-47", size = {640, 360}, out = "cubist"}
