-- xpcall's handler runs under the budget; io.open and io.lines check the opened file; render
-- requests need folders of their own.
print(xpcall(error, function(m) return 'handled' end, 'boom'))
print(xpcall(function(a, b) return a + b end, print, 1, 2))
local f = io.open('note.txt', 'w')
if f then f:write('x') f:close() end
print(pcall(io.open, 'note.txt', 'a+'), pcall(io.lines, 'missing.txt'), io.open('nothere', 'r'))
for l in io.lines('../out/note.txt') do print(l) end
vdg.render{out = 'a'}
print(pcall(vdg.render, {out = 'a/b'}), pcall(vdg.render, {out = '.'}), pcall(vdg.render, {out = 'ab'}))
xpcall(error, function() while true do end end)
