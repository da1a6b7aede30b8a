local crowd = {}
for i = 1, 20 do crowd[i] = vdg.group{name = 'm' .. i, translation = {i % 5, 0, i // 5}} end
vdg.for_each(crowd, function(node, i)
  vdg.change(node, 'rotation', vdg.quat.axis_angle({0, 1, 0}, i * 18), 0, 48, vdg.ease.make('sinusoidal', 0.2, 0.8))
end)
vdg.change(crowd, 'translation', {0, 1, 0}, 10, 20, 'sine')
vdg.render{frames = '1-48', size = {320, 180}, out = 'crowd'}
