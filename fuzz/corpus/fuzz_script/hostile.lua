local ok, e = pcall(function() while true do end end)
local t = setmetatable({}, {__index = function(t, k) return k end})
print(pcall(io.open, '/etc/passwd'), pcall(io.open, '../x', 'w'), pcall(string.rep, 'x', 1 << 30))
error({})
