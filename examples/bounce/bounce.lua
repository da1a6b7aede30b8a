-- A bouncing ball that squashes on impact: actors (Parent, Computer Animation, 4.8) and affine
-- squash and stretch (Parent 4.10).
--
-- Nothing here is key-framed. Each frame, in frame order from the shot's first, the actors run:
--   ball    falls under gravity; "if the ball is near a wall, bounce": when it reaches one of the
--           three walls (the floor, the left wall, the leaning right wall) it reflects its velocity
--           about the wall's normal, squashes along that normal, and sends the wall a message;
--   walls   each flashes when a message says it was hit, harder for a harder hit, then fades.
--
-- Squash and stretch is an affine map of the ball (Parent 4.10): a scale s along a unit axis a and
-- 1/sqrt(s) across it, M = s a a^T + (I - a a^T) / sqrt(s), whose determinant s * (1/sqrt(s))^2 = 1
-- keeps the volume. The link transforms are T R S (scale along the node's own axes), so the axis is
-- turned onto Y, scaled there and turned back, with three nodes:
--   ball (T: where it is) -> ball_axis (R: Y onto a) -> ball_squash (S: 1/sqrt(s), s, 1/sqrt(s))
--     -> ball_spin (R^T, then the ball's roll) -> two hemispheres
-- so ball_spin's object-to-ball matrix is R S R^T Spin = M Spin. On impact a is the wall's normal and
-- s < 1 (squash), recovering with an overshoot (s > 1: stretch as it leaves); in flight a is the
-- direction of travel and s > 1 (stretch, more the faster it goes).
--
--   vdg run examples/bounce/bounce.lua -o out        # out/bounce/frame_0000.png ...
--   vdg run examples/bounce/bounce.lua -o out --frames 50-60   # the same bytes as those frames of a full run

local kFps = 24
local kDt = 1 / kFps        -- seconds per frame
local kGravity = 9.8        -- m/s^2
local kRestitution = 0.8    -- normal speed kept by a bounce
local kRadius = 0.6         -- m
local kSquashPerSpeed = 0.07   -- squash 1 - s per m/s of normal speed at impact
local kMinSquash = 0.5
local kStretchPerSpeed = 0.025 -- stretch s - 1 per m/s of speed in flight
local kMaxStretch = 0.3
local kRecoveryFrames = 8      -- frames of the squash's damped recovery
local kRestingSpeed = 0.8      -- m/s: slower normal hits only stop the ball (no bounce, no squash)

-- Vectors as {x, y, z}.
local function add(a, b, k) k = k or 1; return {a[1] + k * b[1], a[2] + k * b[2], a[3] + k * b[3]} end
local function dot(a, b) return a[1] * b[1] + a[2] * b[2] + a[3] * b[3] end
local function len(a) return math.sqrt(dot(a, a)) end

-- A box [x0, x1] x [y0, y1] x [z0, z1] (counter-clockwise faces seen from outside).
local function box(x0, x1, y0, y1, z0, z1)
  local p = {x0, y0, z0, x1, y0, z0, x1, y1, z0, x0, y1, z0, x0, y0, z1, x1, y0, z1, x1, y1, z1, x0, y1, z1}
  local t = {1, 4, 3, 1, 3, 2, 5, 6, 7, 5, 7, 8, 1, 2, 6, 1, 6, 5, 4, 8, 7, 4, 7, 3, 1, 5, 8, 1, 8, 4, 2, 3, 7, 2, 7, 6}
  return vdg.mesh{positions = p, triangles = t}
end

-- Half a UV sphere of radius kRadius: y >= 0 (upper) or y <= 0.
local function hemisphere(upper, rings, segments)
  local p, t = {}, {}
  local sign = upper and 1 or -1
  local function vertex(phi, theta)
    p[#p + 1] = kRadius * math.sin(phi) * math.cos(theta)
    p[#p + 1] = sign * kRadius * math.cos(phi)
    p[#p + 1] = kRadius * math.sin(phi) * math.sin(theta)
  end
  vertex(0, 0)  -- the pole: vertex 1
  for r = 1, rings do
    for s = 0, segments - 1 do vertex(0.5 * math.pi * r / rings, 2 * math.pi * s / segments) end
  end
  local function at(r, s) return 1 + (r - 1) * segments + s % segments + 1 end
  local function tri(a, b, c)
    if upper then t[#t + 1] = a; t[#t + 1] = c; t[#t + 1] = b
    else t[#t + 1] = a; t[#t + 1] = b; t[#t + 1] = c end
  end
  for s = 0, segments - 1 do tri(1, at(1, s), at(1, s + 1)) end
  for r = 1, rings - 1 do
    for s = 0, segments - 1 do
      tri(at(r, s), at(r + 1, s), at(r + 1, s + 1))
      tri(at(r, s), at(r + 1, s + 1), at(r, s + 1))
    end
  end
  -- the flat cap closing the half at y = 0
  p[#p + 1] = 0; p[#p + 1] = 0; p[#p + 1] = 0
  local centre = #p // 3
  for s = 0, segments - 1 do tri(centre, at(rings, s + 1), at(rings, s)) end
  return vdg.mesh{positions = p, triangles = t}
end

-- The room: a floor, a wall on the left, a wall leaning out on the right (30 degrees).
local c30, s30 = math.cos(math.rad(30)), math.sin(math.rad(30))
local floor = vdg.node{name = "floor", object = box(-5.2, 6.5, -0.3, 0, -1.6, 1.6), color = {0.62, 0.62, 0.58}}
local left = vdg.node{name = "left_wall", object = box(-5.2, -4.5, 0, 5.5, -1.6, 1.6), color = {0.45, 0.55, 0.7}}
local right = vdg.node{name = "right_wall", object = box(0, 0.5, 0, 6.2, -1.6, 1.6), color = {0.7, 0.5, 0.45},
                       translation = {4, 0, 0}, rotation = vdg.quat.axis_angle({0, 0, 1}, -30)}

-- A wall actor: flashes towards pale yellow when told it was hit, then fades back to its colour.
local kFlash = {1, 0.95, 0.55}
local function wall_actor(name, node, color)
  return vdg.actor{
    name = name, node = node, state = {flash = 0, color = color},
    receive = function(self, hit, sender)
      self.state.flash = math.min(1, self.state.flash + hit.speed / 8)
    end,
    update = function(self, frame)
      local st = self.state
      local k = st.flash
      self:set("color", {st.color[1] + k * (kFlash[1] - st.color[1]), st.color[2] + k * (kFlash[2] - st.color[2]),
                         st.color[3] + k * (kFlash[3] - st.color[3])})
      st.flash = st.flash * 0.8
    end}
end

-- Each wall is a plane n . p = d with n pointing into the room, and the actor to tell.
local walls = {
  {n = {0, 1, 0}, d = 0, actor = wall_actor("floor", floor, {0.62, 0.62, 0.58})},
  {n = {1, 0, 0}, d = -4.5, actor = wall_actor("left_wall", left, {0.45, 0.55, 0.7})},
  {n = {-c30, s30, 0}, d = -4 * c30, actor = wall_actor("right_wall", right, {0.7, 0.5, 0.45})},
}

-- The ball's nodes (see the top).
local ball = vdg.group{name = "ball", translation = {-3, 4, 0}}
local axis = vdg.group{name = "ball_axis", parent = ball}
local squash = vdg.group{name = "ball_squash", parent = axis}
local spin = vdg.group{name = "ball_spin", parent = squash}
vdg.node{name = "ball_top", parent = spin, object = hemisphere(true, 8, 32), color = {0.95, 0.35, 0.15}}
vdg.node{name = "ball_bottom", parent = spin, object = hemisphere(false, 8, 32), color = {0.98, 0.9, 0.3}}

-- The rotation that turns Y onto the unit vector a.
local function y_onto(a)
  local c = a[2]
  if c > 1 - 1e-12 then return vdg.quat.identity() end
  if c < -1 + 1e-12 then return vdg.quat.axis_angle({1, 0, 0}, 180) end
  return vdg.quat.axis_angle({a[3], 0, -a[1]}, math.deg(math.acos(c)))  -- axis Y x a
end

vdg.actor{
  name = "ball", node = ball, drives = {axis, squash, spin},
  state = {p = {-3, 4, 0}, v = {4.5, 0, 0}, roll = 0, since = math.huge, normal = {0, 1, 0}, s0 = 1},
  update = function(self, frame)
    local st = self.state
    -- Motion: gravity, then the walls ("if the ball is near the wall, bounce").
    st.v = add(st.v, {0, -kGravity * kDt, 0})
    st.p = add(st.p, st.v, kDt)
    st.since = st.since + 1
    for _, w in ipairs(walls) do
      local gap = dot(w.n, st.p) - w.d - kRadius
      local vn = dot(w.n, st.v)
      if gap < 0 and vn < 0 then
        st.p = add(st.p, w.n, -gap)
        if -vn > kRestingSpeed then
          st.v = add(st.v, w.n, -(1 + kRestitution) * vn)
          st.since, st.normal = 0, w.n
          st.s0 = math.max(kMinSquash, 1 + kSquashPerSpeed * vn)
          self:send(w.actor, {speed = -vn})
        else
          st.v = add(st.v, w.n, -vn)  -- resting contact: the normal speed goes
        end
      end
    end
    st.roll = st.roll - math.deg(st.v[1] * kDt / kRadius)  -- rolls the way it travels
    -- Squash and stretch: along the wall's normal while the impact recovers (a damped
    -- oscillation: squash, then a little stretch), along the travel in flight.
    local a, s, offset = st.normal, 1, 0
    if st.since < kRecoveryFrames then
      local k = st.since
      s = 1 - (1 - st.s0) * math.cos(1.3 * k) * math.exp(-0.5 * k)
      if s < 1 then offset = kRadius * (1 - s) end  -- the squashed ball still touches the wall
    else
      local speed = len(st.v)
      local ramp = math.min(1, (st.since - kRecoveryFrames) / kRecoveryFrames)
      if speed > 1e-9 then a = {st.v[1] / speed, st.v[2] / speed, st.v[3] / speed} end
      s = 1 + ramp * math.min(kMaxStretch, kStretchPerSpeed * speed)
    end
    local turn = y_onto(a)
    self:set("translation", add(st.p, st.normal, -offset))
    self:set(axis, "rotation", turn)
    self:set(squash, "scale", {1 / math.sqrt(s), s, 1 / math.sqrt(s)})
    self:set(spin, "rotation", turn:inverse() * vdg.quat.axis_angle({0, 0, 1}, st.roll))
  end}

local centre = vdg.group{name = "centre", translation = {0.6, 2.2, 0}}
vdg.camera{name = "camera", translation = {0.6, 5.5, 12}, look_at = centre, fov = 44}
vdg.render{frames = "0-143", size = {480, 320}, out = "bounce"}
