-- Rademacher 99, Figure 13: a scene of view-dependent objects seen by one moving camera.
--  - a static view-dependent head (head/head.vdg.json, made by make_head.py): ears flared when seen
--    from the front, a long nose in profile;
--  - an animated view-dependent body: the walking character of section 4 (../walk), its arm and
--    leg swing exaggerated by keys at frames 10 and 30, seen from the front and the side;
--  - background buildings with one key each (../building): distorted face-on, turning into plain
--    boxes as the camera passes to their sides (the "cosine" uncovered mode).
-- The camera moves along an eased Catmull-Rom path (Parent 4.4), always looking at the head: a
-- moving centre of interest.
--
--   python3 examples/figure13/make_head.py          (regenerates head/; the files are committed)
--   vdg run examples/figure13/figure13.lua --root examples -o out
-- (--root: the script loads ../walk and ../building, so it may read below examples/)

local building = vdg.load("../building/building.vdg.json")
local walker = vdg.load("../walk/walker.vdg.json")
local head = vdg.load("head/head.vdg.json")
local up = {0, 1, 0}

-- The street: buildings on both sides, their fronts (+Z, where their key is) turned to the street.
local kFacades = {{0.92, 0.78, 0.62}, {0.7, 0.8, 0.9}, {0.85, 0.85, 0.7}, {0.8, 0.7, 0.75}}
local street = vdg.group{name = "street"}
for i = 0, 3 do
  for _, side in ipairs({-1, 1}) do
    vdg.node{name = string.format("building_%s%d", side < 0 and "left" or "right", i), object = building,
             parent = street, translation = {side * 4.2, 0, -i * 2.8 - 2.0},
             rotation = vdg.quat.axis_angle(up, -side * 90), color = kFacades[(i + (side + 1) // 2) % 4 + 1]}
  end
end

-- The character: the walker walks towards the camera's side of the street (its cycle is 40
-- frames, in place; the body node carries it forward), the head sits on its shoulders and hides
-- the walker's own small head inside it.
local body = vdg.node{name = "body", object = walker, translation = {0, 0, -5}, color = {0.85, 0.4, 0.35}}
vdg.change(body, "translation", {0, 0, 3.4}, 0, 95)
local character_head = vdg.node{name = "head", object = head, parent = body, translation = {0, 1.72, 0.01},
                                placement = {scale = 0.24}, color = {0.98, 0.85, 0.65}}

-- The camera: from the left of the street round to the front and on to the right, easing in and
-- out, looking at the head all the time.
vdg.camera{name = "camera", look_at = character_head, fov = 32,
           path = {points = {{-4.0, 2.2, 3.5}, {-1.6, 1.9, 5.0}, {1.4, 1.8, 5.2}, {3.8, 2.1, 3.6}},
                   interpolation = "catmull-rom", ease = vdg.ease.make("sinusoidal", 0.25, 0.75),
                   start = 0, ["end"] = 95}}

vdg.render{frames = "0-95", size = {640, 360}, out = "figure13"}
