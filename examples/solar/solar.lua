-- The sun, the earth and the moon: Parent's transformation hierarchy (Computer Animation, 4.7).
--
--   E' = E Te Re        the earth: moved out along x (Te), then turned about the sun (Re)
--   M' = M Tm Rm Te Re  the moon: moved out from the earth (Tm), turned about it (Rm), then
--                       carried along by the earth's own transformations
--
-- As a tree (column vectors, each node's link relative to its parent):
--   sun;  earth_orbit (Re) -> earth (Te) -> moon_orbit (Rm) -> moon (Tm)
-- Distances are not to scale (93 million and 220 thousand miles would hide the moon); the periods
-- are: one frame is four days, the earth goes round in 365 days, the moon in 28.
--
--   vdg run examples/solar/solar.lua -o out

-- A UV sphere of radius 1, built here: the language has loops and functions.
local function sphere(rings, segments)
  local p, t = {}, {}
  local function add(x, y, z) p[#p + 1] = x; p[#p + 1] = y; p[#p + 1] = z end
  add(0, 1, 0)
  for r = 1, rings - 1 do
    local phi = math.pi * r / rings
    for s = 0, segments - 1 do
      local theta = 2 * math.pi * s / segments
      add(math.sin(phi) * math.sin(theta), math.cos(phi), math.sin(phi) * math.cos(theta))
    end
  end
  add(0, -1, 0)
  local south = 1 + (rings - 1) * segments
  local function ring(r, s) return 1 + (r - 1) * segments + s % segments end
  -- vdg.mesh counts vertices from 1, as Lua lists and OBJ faces do
  local function tri(a, b, c) t[#t + 1] = a + 1; t[#t + 1] = b + 1; t[#t + 1] = c + 1 end
  for s = 0, segments - 1 do tri(0, ring(1, s), ring(1, s + 1)) end
  for r = 1, rings - 2 do
    for s = 0, segments - 1 do
      tri(ring(r, s), ring(r + 1, s), ring(r + 1, s + 1))
      tri(ring(r, s), ring(r + 1, s + 1), ring(r, s + 1))
    end
  end
  for s = 0, segments - 1 do tri(south, ring(rings - 1, s + 1), ring(rings - 1, s)) end
  return vdg.mesh{positions = p, triangles = t}
end

local ball = sphere(16, 24)
local kDaysPerFrame = 4
local kYear, kMonth = 365, 28  -- days for one turn of Re and of Rm
local up = {0, 1, 0}

-- The size of each body is its placement (it does not carry over to its children); the links
-- carry the motion.
vdg.node{name = "sun", object = ball, placement = {scale = 1.6}, color = {1.0, 0.78, 0.15}}
local earth_orbit = vdg.group{name = "earth_orbit"}                        -- Re
local earth = vdg.node{name = "earth", object = ball, parent = earth_orbit,  -- Te
                       translation = {8, 0, 0}, placement = {scale = 0.6}, color = {0.2, 0.45, 0.95}}
local moon_orbit = vdg.group{name = "moon_orbit", parent = earth}           -- Rm
vdg.node{name = "moon", object = ball, parent = moon_orbit,                 -- Tm
         translation = {1.8, 0, 0}, placement = {scale = 0.25}, color = {0.75, 0.75, 0.72}}

-- Re and Rm advance with the day: CHANGE the rotation by a quarter turn over each quarter period.
local frames = kYear / kDaysPerFrame
for q = 0, 3 do
  vdg.change(earth_orbit, "rotation", vdg.quat.axis_angle(up, 90), q * frames / 4, (q + 1) * frames / 4)
end
local month = kMonth / kDaysPerFrame
for q = 0, math.ceil(frames / month) * 4 - 1 do
  vdg.change(moon_orbit, "rotation", vdg.quat.axis_angle(up, 90), q * month / 4, (q + 1) * month / 4)
end

vdg.camera{name = "camera", translation = {0, 9, 13}, look_at = earth_orbit, fov = 45}
print(string.format("one year = %.2f frames, one lunar month = %.2f frames", frames, month))
vdg.render{frames = {0, math.floor(frames)}, size = {480, 320}, out = "solar"}
