local n = vdg.group{name = 'n'}
vdg.track(n, 'translation', {{0, {0, 0, 0}}, {10, {1, 2, 3}, ease = vdg.ease.make('parabolic', 0.3, 0.6)}, {20, {0, 0, 0}}},
          'catmull-rom', 'loop')
vdg.track(n, 'rotation', {{0, vdg.quat.identity()}, {12, {0, 0, 1, 0}}}, 'slerp')
local b = vdg.group{name = 'b'}
vdg.track(b, 'scale', {{0, {1, 1, 1}, out = {2, 1, 1}}, {5, {2, 2, 2}, ['in'] = {1, 2, 2}}}, 'bezier')
