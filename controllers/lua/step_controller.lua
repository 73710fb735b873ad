--[==[
step_controller.lua: a lock-step controller for sim_server, written in Lua 5.2 on the tongue_lcm
bindings that lcm-gen generates, to show that the bus does not care which language a controller
is written in.

usage: step_controller.lua [--lcm-url URL] [--prefix TONGUE_] [--max-steps N]
                           [--timeout-ms MS] MUSCLE=LEVEL[@START[:END]] ...

It reads the model (sent by the server at start; asked for with "describe" if it has not come
within 250 ms), checks that every MUSCLE is one of the model's, then answers each state k the
server publishes with the activation tagged k + 1: every muscle of the command line, each at its
level for step k + 1, in one message (muscles it does not name keep their levels in the server).
With --max-steps N it ends (exit 0) once the state of step N has arrived; otherwise it runs until
the server falls silent.

MUSCLE=LEVEL        the muscle at LEVEL (a fraction of its maximum force, in [0, 1]) throughout;
MUSCLE=LEVEL@START  from time START (s) on, 0 before;
MUSCLE=LEVEL@START:END
                    from START until END (s), 0 outside.
Step k + 1 runs from the time t of state k to t + dt; a window [START, END) holds for the steps
that start in it, START and END rounded to the nearest step start (t >= START - dt/2 and
t < END - dt/2, dt from the model), so that a time on the step grid is never split by round-off.
Where several entries name one muscle, the last whose window holds sets its level.

--lcm-url URL    LCM provider (default udpm://239.255.76.67:7667?ttl=0&recv_buf_size=4194304)
--prefix P       channel prefix of the server (default TONGUE_)
--max-steps N    stop after answering state N - 1 and seeing state N
--timeout-ms MS  give up (exit 4) when nothing comes from the server for MS ms (default 10000)

Start it before the server (it answers states from step 0 on; a server already waiting for a
step it never saw is not answered). Several instances may drive one server started with
--controllers N, each naming its own muscles.

A state published again for a step already answered (the server repeats it when the answer is
late, e.g. lost) is answered with the very message sent for it, which the server takes once.
The activations name their sender, "step_controller:<pid>"; a rejection notice of the server
(<prefix>REJECTION) about the last one sent ends the controller (exit 5) with its reason.

Exit status: 0 state N reached; 1 a bad command line, a muscle not in the model, or LCM
failed; 2 a step failed to converge; 4 the server fell silent; 5 the server rejected the
activation.
Run it with the generated bindings on the Lua path: the build's wrapper
build/controllers/lua/step_controller does that.
]==]

local lcm = require("lcm")
local tongue_lcm = require("tongue_lcm")

local PROG = "step_controller"
-- The same as kDefaultLcmUrl in sim_server/bus/channels.hpp (the C++ definition): keep them equal.
local DEFAULT_URL = "udpm://239.255.76.67:7667?ttl=0&recv_buf_size=4194304"
-- The exit codes of sim_server/common/exit_code.hpp (docs/exit_codes.md).
local EXIT_ERROR = 1
local EXIT_NOT_CONVERGED = 2
local EXIT_TIMEOUT = 4
local EXIT_REJECTED = 5
local SLICE_MS = 50             -- longest single wait on the bus
local DESCRIBE_AFTER_MS = 250   -- ask for the model when it has not come by then

-- The largest model and state taken [bytes], as sim_server/bus/receive_limits.hpp states them
-- (kModelLimit, kStateLimitBeforeModel, kRejectionLimit).
local MODEL_LIMIT = 64 * 1024 * 1024
local STATE_LIMIT = 32 * 1024 * 1024
local REJECTION_LIMIT = 8192
-- Characters of a notice's reason shown (a sentence naming a muscle and a step).
local REASON_SHOWN = 300

-- Received text as a report prints it: bytes outside printable ASCII as \xNN, cut at max_shown
-- (default 64).
local function printable(text, max_shown)
  max_shown = max_shown or 64
  local shown = text:sub(1, max_shown):gsub("[^\32-\126]", function(c)
    return string.format("\\x%02x", c:byte())
  end)
  if #text > max_shown then shown = shown .. "...(" .. #text .. " bytes)" end
  return shown
end

local function fail(status, text)
  io.stderr:write(PROG .. ": " .. text .. "\n")
  os.exit(status)
end

local function usage_error(text)
  fail(EXIT_ERROR, text .. "\nusage: step_controller.lua [--lcm-url URL] [--prefix TONGUE_] " ..
          "[--max-steps N] [--timeout-ms MS] MUSCLE=LEVEL[@START[:END]] ...")
end

-- A whole number >= minimum from text, or nil.
local function whole_number(text, minimum)
  local value = tonumber(text)
  if value == nil or value ~= math.floor(value) or value < minimum or value > 2 ^ 53 then
    return nil
  end
  return value
end

-- One MUSCLE=LEVEL[@START[:END]] entry; times in s.
local function parse_entry(text)
  local name, level_text, window = text:match("^([^=]+)=([^@]+)@?(.*)$")
  if name == nil then
    usage_error("'" .. text .. "' is not MUSCLE=LEVEL[@START[:END]]")
  end
  local level = tonumber(level_text)
  if level == nil or level ~= level or level < 0 or level > 1 then
    usage_error("'" .. text .. "': the level must be a number in [0, 1]")
  end
  local entry = {name = name, level = level, start = 0, finish = math.huge}
  if window ~= "" then
    local start_text, end_text = window:match("^([^:]+):?(.*)$")
    entry.start = tonumber(start_text or "")
    if entry.start == nil or entry.start < 0 then
      usage_error("'" .. text .. "': START must be a time >= 0 s")
    end
    if end_text ~= "" then
      entry.finish = tonumber(end_text)
      if entry.finish == nil or entry.finish <= entry.start then
        usage_error("'" .. text .. "': END must be a time > START (s)")
      end
    end
  end
  return entry
end

local function parse_arguments(args)
  local options = {url = DEFAULT_URL, prefix = "TONGUE_", timeout_ms = 10000, entries = {}}
  local i = 1
  while i <= #args do
    local arg = args[i]
    local key, value = arg:match("^(%-%-[%w-]+)=(.*)$")
    key = key or arg
    local function take()
      if value == nil then
        i = i + 1
        value = args[i]
        if value == nil then usage_error(key .. " needs a value") end
      end
      return value
    end
    if key == "--help" or key == "-h" then
      io.stdout:write("usage: step_controller.lua [--lcm-url URL] [--prefix TONGUE_] " ..
                      "[--max-steps N] [--timeout-ms MS] MUSCLE=LEVEL[@START[:END]] ...\n")
      os.exit(0)
    elseif key == "--lcm-url" then
      options.url = take()
    elseif key == "--prefix" then
      options.prefix = take()
      if not options.prefix:match("^[A-Z0-9_]*$") then
        usage_error("--prefix must contain only A-Z, 0-9 and _, not '" .. options.prefix .. "'")
      end
    elseif key == "--max-steps" then
      options.max_steps = whole_number(take(), 1)
      if options.max_steps == nil then usage_error("--max-steps must be an integer >= 1") end
    elseif key == "--timeout-ms" then
      options.timeout_ms = whole_number(take(), 1)
      if options.timeout_ms == nil then usage_error("--timeout-ms must be an integer >= 1") end
    elseif arg:sub(1, 1) == "-" then
      usage_error("unknown option '" .. arg .. "'")
    else
      table.insert(options.entries, parse_entry(arg))
    end
    i = i + 1
  end
  if #options.entries == 0 then usage_error("no MUSCLE=LEVEL given") end
  return options
end

-- The muscles the entries name, each once, in the order of their first entry.
local function named_muscles(entries)
  local names, seen = {}, {}
  for _, entry in ipairs(entries) do
    if not seen[entry.name] then
      seen[entry.name] = true
      table.insert(names, entry.name)
    end
  end
  return names
end

-- The level of muscle for the step that starts at time t (s), steps dt (s) long.
local function level_at(entries, muscle, t, dt)
  local level = 0
  for _, entry in ipairs(entries) do
    if entry.name == muscle and t >= entry.start - dt / 2 and t < entry.finish - dt / 2 then
      level = entry.level
    end
  end
  return level
end

local function main(args)
  local options = parse_arguments(args)
  local names = named_muscles(options.entries)
  local channel = {
    activation = options.prefix .. "ACTIVATION",
    state = options.prefix .. "STATE",
    model = options.prefix .. "MODEL",
    command = options.prefix .. "COMMAND",
    rejection = options.prefix .. "REJECTION",
  }
  -- The process id, from Linux's /proc (plain Lua has no getpid).
  local stat = io.open("/proc/self/stat")
  local sender = PROG .. ":" .. (stat and stat:read("*n") or "unknown")
  if stat then stat:close() end
  local sent  -- the last activation sent: {msg = ..., bytes = ...}

  local ok, bus = pcall(lcm.lcm.new, options.url)
  if not ok then fail(EXIT_ERROR, "cannot open the LCM bus at '" .. options.url .. "': " .. bus) end
  local model
  local states = {}  -- received, not yet answered, in order
  -- Any process on the bus can send on these channels: a message too large, or one lcm-gen's
  -- decoder fails on, is counted and reported (at most once a second), never fatal.
  local rejected, reported_at = 0, nil
  local function take(decoder, data, limit, what)
    local ok, msg = false, "larger than the " .. limit .. "-byte limit"
    if #data <= limit then ok, msg = pcall(decoder, data) end
    if ok and msg ~= nil then return msg end
    rejected = rejected + 1
    if reported_at ~= os.time() then
      reported_at = os.time()
      io.stderr:write(string.format("%s: rejected %s (%d so far): %s\n", PROG, what, rejected,
                                    printable(tostring(msg))))
    end
    return nil
  end
  bus:subscribe(channel.model, function(_, data)
    model = take(tongue_lcm.lcmt_tongue_model.decode, data, MODEL_LIMIT, "model") or model
  end)
  bus:subscribe(channel.state, function(_, data)
    local state = take(tongue_lcm.lcmt_tongue_state.decode, data, STATE_LIMIT, "state")
    if state then table.insert(states, state) end
  end)
  bus:subscribe(channel.rejection, function(_, data)
    local notice = take(tongue_lcm.lcmt_tongue_rejection.decode, data, REJECTION_LIMIT,
                        "rejection notice")
    if notice and sent and notice.sender == sender and notice.activation_step == sent.msg.step and
       notice.activation_utime == sent.msg.utime then
      fail(EXIT_REJECTED, string.format("the server rejected its activation for step %d (%s): " ..
                                        "%s: %s", notice.activation_step, sender,
                                        printable(notice.kind), printable(notice.reason,
                                        REASON_SHOWN)))
    end
  end)
  io.stderr:write(string.format("%s: listening on %s, channels %s*\n", PROG, options.url,
                                options.prefix))
  io.stderr:flush()

  -- Handles messages until done() is true; fails after timeout_ms without any message.
  -- on_silence(ms), when given, is called after each empty wait with the silence so far.
  local function wait_until(done, what, on_silence)
    local silent_ms = 0
    while not done() do
      if bus:handle_timeout(SLICE_MS) then
        silent_ms = 0
      else
        silent_ms = silent_ms + SLICE_MS
        if on_silence then on_silence(silent_ms) end
        if silent_ms >= options.timeout_ms then
          fail(EXIT_TIMEOUT,
               string.format("nothing from the server on %s* for %d ms while waiting for %s",
                             options.prefix, options.timeout_ms, what))
        end
      end
    end
  end

  local described = false
  wait_until(function() return model ~= nil end, "the model", function(silent_ms)
    if not described and silent_ms >= DESCRIBE_AFTER_MS then
      local command = tongue_lcm.lcmt_tongue_command:new()
      command.utime = os.time() * 1000000
      command.command = "describe"
      bus:publish(channel.command, command:encode())
      described = true
    end
  end)
  local known = {}
  for _, name in ipairs(model.muscle_names) do known[name] = true end
  for _, name in ipairs(names) do
    if not known[name] then
      fail(EXIT_ERROR, string.format("muscle '%s' is not in the model (its muscles: %s)", name,
                            table.concat(model.muscle_names, ", ")))
    end
  end
  local dt = model.dt
  local answered, last_step, last_time = 0, nil, nil

  while true do
    wait_until(function() return #states > 0 end,
               last_step and ("the state of step " .. (last_step + 1)) or "the first state")
    local state = table.remove(states, 1)
    last_step, last_time = state.step, state.time
    if not state.converged then
      fail(EXIT_NOT_CONVERGED, string.format("the server reports step %d did not converge: %s",
                                             state.step + 1, printable(state.status)))
    end
    if options.max_steps and state.step >= options.max_steps then break end
    if sent and sent.msg.step == state.step + 1 then
      -- The step answered last, again ("paused", or repeated after a loss): the same message.
      bus:publish(channel.activation, sent.bytes)
    else
      local msg = tongue_lcm.lcmt_tongue_activation:new()
      msg.utime = os.time() * 1000000
      msg.step = state.step + 1
      msg.num_muscles = #names
      msg.names = names
      msg.levels = {}
      for i, name in ipairs(names) do
        msg.levels[i] = level_at(options.entries, name, state.time, dt)
      end
      msg.sender = sender
      sent = {msg = msg, bytes = msg:encode()}
      bus:publish(channel.activation, sent.bytes)
      answered = answered + 1
    end
  end
  io.stderr:write(string.format("%s: answered %d states; reached step %d (t = %.6g s)%s\n", PROG,
                                answered, last_step, last_time,
                                rejected > 0 and string.format("; %d messages rejected", rejected)
                                  or ""))
  return 0
end

os.exit(main(arg))
