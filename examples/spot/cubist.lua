-- The cubist Spot (spot-cubist.vdg.json, per-part key sets; docs/weights.md) beside the plain one,
-- while the camera circles them. The plain cow (left) blends its five keys for the camera's view
-- everywhere; the cubist cow (middle) does so for its body only: its head is a part with a fixed
-- driving view, so it keeps the front drawing (ears flared, horns spread) from every side. The
-- third cow (right) is the cubist model again with its head driven by another node: a "muse" that
-- circles the other way round, so the head shows the drawing made from the muse's side while the
-- body shows the camera's (part_drivers; a camera node drives by its eye on its path).
--
--   vdg run examples/spot/cubist.lua --root examples -o out
local plain = vdg.load("spot.vdg.json")
local cubist = vdg.load("spot-cubist.vdg.json")
local trio = vdg.group{name = "trio"}
local muse = vdg.group{name = "muse", parent = trio}
vdg.track(muse, "translation", {{0, {0, 1, 9}}, {12, {-9, 1, 0}}, {24, {0, 1, -9}}, {36, {9, 1, 0}}, {47, {0, 1, 9}}})
vdg.node{name = "plain", object = plain, parent = trio, translation = {-2.4, 0, 0}}
vdg.node{name = "cubist", object = cubist, parent = trio, translation = {0, 0, 0}}
vdg.node{name = "muse-led", object = cubist, parent = trio, translation = {2.4, 0, 0}, part_drivers = {head = muse}}
local focus = vdg.group{name = "focus", parent = trio, translation = {0, 0.25, 0}}
vdg.camera{name = "camera", look_at = focus, fov = 40,
           path = {points = {{0, 1.6, -7.5}, {7.5, 1.6, 0}, {0, 1.6, 7.5}, {-7.5, 1.6, 0}, {0, 1.6, -7.5}}, start = 0, ["end"] = 47}}
vdg.render{frames = "0-47", size = {640, 360}, out = "cubist"}
