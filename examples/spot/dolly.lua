-- A dolly in on Spot (examples/spot/spot-dolly.vdg.json, keys at distances): the camera starts at
-- the front key's wide shot and moves straight in to the close-up's eye; the blend follows the
-- eye's POSITION, so the cow turns from the wide key's drawing into the close-up's (snout toned
-- down, ears flared) as the camera nears, with no pop where the eye leaves the keys' hull.
--
--   vdg run examples/spot/dolly.lua -o out
local spot = vdg.load("spot-dolly.vdg.json")
local cow = vdg.node{name = "spot", object = spot}
-- The front keys' eyes (spot-dolly.vdg.json): wide at distance 4, close-up at 1.6 from the centre.
vdg.camera{name = "camera", look_at = cow, fov = 40,
           path = {points = {{0, 1.2, -7}, {0, 0.7017928231593482, -3.76569990571109},
                             {0, 0.34577573612676116, -1.392252658827176}}, start = 0, ["end"] = 24}}
vdg.render{frames = "0-24", size = {320, 240}, out = "dolly"}
