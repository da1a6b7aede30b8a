-- Two actors and a message (docs/language.md, "Actors"): a seed for the fuzzer.
local ball = vdg.group{name = "ball"}
local wall = vdg.group{name = "wall"}
vdg.actor{name = "mover", node = ball, state = {x = 0, v = 0.2},
  update = function(self, frame)
    self.state.x = self.state.x + self.state.v
    if self.state.x > 1 then self.state.v = -self.state.v; self:send("wall", {hit = frame}) end
    self:set("translation", {self.state.x, 0, 0})
  end}
vdg.actor{name = "wall", node = wall, state = {hits = 0},
  receive = function(self, message) self.state.hits = self.state.hits + 1 end,
  update = function(self, frame) self:set("scale", 1 + 0.1 * self.state.hits) end}
vdg.render{frames = "0-20", size = {64, 48}, out = "actors"}
