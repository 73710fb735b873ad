function status = step_controller(varargin)
%STEP_CONTROLLER A lock-step controller for sim_server in MATLAB, on LCM's Java bindings.
%   status = step_controller('--max-steps', '30', 'SG_left=0.125@0:0.12', 'SG_right=0.125@0:0.12')
%   step_controller --max-steps 30 SG_left=0.125@0:0.12 SG_right=0.125@0:0.12
%
%   usage: step_controller [--lcm-url URL] [--prefix TONGUE_] [--max-steps N]
%                          [--timeout-ms MS] MUSCLE=LEVEL[@START[:END]] ...
%
%   The Java controller controllers/java/StepController.java line for line (the same options,
%   MessageAggregator polling loop, messages and statuses), so that what the Java program is
%   tested to do against sim_server, this does too; its header says what every option means.
%   Every argument is text, as on a command line. It reads the model (asking with "describe" if
%   none has come within 250 ms), then answers each state k of the server with the activation
%   tagged k + 1, until the state of step N (--max-steps N) or until the server falls silent.
%   Messages go to stderr; status is the exit status the other controllers give: 0 state N
%   reached, 1 a bad command line, a muscle not in the model, or LCM failed, 2 a step failed to
%   converge, 4 the server fell silent, 5 the server rejected the activation.
%
%   Before the first call, put LCM's and the project's classes on MATLAB's Java path (both are
%   Java 8 class files, which MATLAB's Java loads):
%     javaaddpath('/usr/share/java/lcm.jar');                      % Debian's liblcm-java
%     javaaddpath('<build>/controllers/java/tongue_lcm.jar');      % built by the project
%   From a shell: matlab -batch "exit(step_controller('--max-steps', '30', 'SG_left=0.125'))"

k = constants();
% What the nested functions share: the bus and what has been received from it.
options = [];
channel_state = '';
channel_model = '';
channel_rejection = '';
sender = '';
aggregator = [];
model = [];
states = {};  % received, not yet answered
sent_msg = [];  % the last activation sent, and its bytes
sent_bytes = [];
rejected = 0;
reported_at = -1;

try
  status = drive(varargin);
catch failure
  failure_status = regexp(failure.identifier, '^step_controller:exit(\d+)$', 'tokens', 'once');
  if isempty(failure_status)
    fprintf(2, '%s: LCM failed: %s\n', k.PROG, failure.message);
    status = k.EXIT_ERROR;
  else
    fprintf(2, '%s: %s\n', k.PROG, failure.message);
    status = str2double(failure_status{1});
  end
end

  % Any process on the bus can send on these channels: a message too large, or one lcm-gen's
  % decoder fails on, is counted and reported (at most once a second), never fatal.
  function msg = take(decoder, data, limit, what)
    reason = sprintf('larger than the %d-byte limit', limit);
    if numel(data) <= limit
      try
        msg = decoder(data);
        return;
      catch cause
        reason = cause.message;
      end
    end
    rejected = rejected + 1;
    second = floor(java.lang.System.currentTimeMillis() / 1000);
    if second ~= reported_at
      reported_at = second;
      fprintf(2, '%s: rejected %s (%d so far): %s\n', k.PROG, what, rejected, ...
              printable(reason, 64));
    end
    msg = [];
  end

  % Waits up to SLICE_MS for one message and handles it; false when none came.
  function received = handle_next()
    message = aggregator.getNextMessage(k.SLICE_MS);
    received = ~isempty(message);
    if ~received
      return;
    end
    channel = char(message.channel);
    if strcmp(channel, channel_model)
      model_received = take(@(data) tongue_lcm.lcmt_tongue_model(data), message.data, ...
                            k.MODEL_LIMIT, 'model');
      if ~isempty(model_received), model = model_received; end
    elseif strcmp(channel, channel_state)
      state = take(@(data) tongue_lcm.lcmt_tongue_state(data), message.data, k.STATE_LIMIT, ...
                   'state');
      if ~isempty(state), states{end + 1} = state; end
    elseif strcmp(channel, channel_rejection)
      notice = take(@(data) tongue_lcm.lcmt_tongue_rejection(data), message.data, ...
                    k.REJECTION_LIMIT, 'rejection notice');
      if ~isempty(notice) && ~isempty(sent_msg) && strcmp(char(notice.sender), sender) ...
          && notice.activation_step == sent_msg.step && notice.activation_utime == sent_msg.utime
        fail(k.EXIT_REJECTED, sprintf( ...
            'the server rejected its activation for step %d (%s): %s: %s', ...
            notice.activation_step, sender, printable(char(notice.kind), 64), ...
            printable(char(notice.reason), k.REASON_SHOWN)));
      end
    end
  end

  % Fails once nothing has come from the server for the timeout.
  function check_silence(silent_ms, what)
    if silent_ms >= options.timeout_ms
      fail(k.EXIT_TIMEOUT, sprintf( ...
          'nothing from the server on %s* for %d ms while waiting for %s', options.prefix, ...
          options.timeout_ms, what));
    end
  end

  % Its output is named apart from step_controller's status: nested functions share names.
  function result = drive(args)
    options = parse_arguments(args);
    if isempty(options)
      result = k.EXIT_OK;
      return;
    end
    names = named_muscles(options.entries);
    channel_activation = [options.prefix 'ACTIVATION'];
    channel_state = [options.prefix 'STATE'];
    channel_model = [options.prefix 'MODEL'];
    channel_command = [options.prefix 'COMMAND'];
    channel_rejection = [options.prefix 'REJECTION'];
    % The process id: the JVM's name is "<pid>@<host>" (MATLAB's own process).
    jvm_name = char(java.lang.management.ManagementFactory.getRuntimeMXBean().getName());
    sender = [k.PROG ':' strtok(jvm_name, '@')];

    bus = bus_at(options.url);
    aggregator = lcm.lcm.MessageAggregator();
    % Java's finally: the aggregator stops taking messages whatever the way out.
    cleanup = onCleanup(@() unsubscribe(bus, {channel_model, channel_state, ...
                                              channel_rejection}, aggregator));
    bus.subscribe(channel_model, aggregator);
    bus.subscribe(channel_state, aggregator);
    bus.subscribe(channel_rejection, aggregator);
    fprintf(2, '%s: listening on %s, channels %s*\n', k.PROG, options.url, options.prefix);

    silent_ms = 0;
    described = false;
    while isempty(model)
      if handle_next(), silent_ms = 0; else, silent_ms = silent_ms + k.SLICE_MS; end
      if ~described && silent_ms >= k.DESCRIBE_AFTER_MS
        command = tongue_lcm.lcmt_tongue_command();
        command.utime = int64(java.lang.System.currentTimeMillis()) * 1000;
        command.command = 'describe';
        bus.publish(channel_command, command);
        described = true;
      end
      check_silence(silent_ms, 'the model');
    end
    known = reshape(cell(model.muscle_names), 1, []);
    for i = 1:numel(names)
      if ~any(strcmp(known, names{i}))
        fail(k.EXIT_ERROR, sprintf('muscle ''%s'' is not in the model (its muscles: %s)', ...
                                   names{i}, strjoin(known, ', ')));
      end
    end
    dt = model.dt;
    answered = 0;
    state = [];

    while true
      if isempty(state)
        what = 'the first state';
      else
        what = sprintf('the state of step %d', state.step + 1);
      end
      silent_ms = 0;
      while isempty(states)
        if handle_next(), silent_ms = 0; else, silent_ms = silent_ms + k.SLICE_MS; end
        check_silence(silent_ms, what);
      end
      state = states{1};
      states(1) = [];
      if ~state.converged
        fail(k.EXIT_NOT_CONVERGED, sprintf('the server reports step %d did not converge: %s', ...
                                           state.step + 1, printable(char(state.status), 64)));
      end
      if options.max_steps >= 0 && state.step >= options.max_steps, break; end
      if ~isempty(sent_msg) && sent_msg.step == state.step + 1
        % The step answered last, again ("paused", or repeated after a loss): the same bytes.
        bus.publish(channel_activation, sent_bytes, 0, numel(sent_bytes));
      else
        msg = tongue_lcm.lcmt_tongue_activation();
        msg.utime = int64(java.lang.System.currentTimeMillis()) * 1000;
        msg.step = int64(state.step + 1);
        msg.num_muscles = int32(numel(names));
        msg.names = java_strings(names);
        % A Java array field reads as a MATLAB copy: filled here, then assigned whole.
        levels = zeros(1, numel(names));
        for i = 1:numel(names)
          levels(i) = level_at(options.entries, names{i}, state.time, dt);
        end
        msg.levels = levels;
        msg.sender = sender;
        sent_msg = msg;
        sent_bytes = encode(msg);
        bus.publish(channel_activation, sent_bytes, 0, numel(sent_bytes));
        answered = answered + 1;
      end
    end
    if rejected > 0
      rejected_text = sprintf('; %d messages rejected', rejected);
    else
      rejected_text = '';
    end
    fprintf(2, '%s: answered %d states; reached step %d (t = %.6g s)%s\n', k.PROG, answered, ...
            state.step, state.time, rejected_text);
    result = k.EXIT_OK;
  end
end

function k = constants()
k.PROG = 'step_controller';
k.USAGE = ['usage: step_controller [--lcm-url URL] [--prefix TONGUE_] ' ...
           '[--max-steps N] [--timeout-ms MS] MUSCLE=LEVEL[@START[:END]] ...'];
% The same as kDefaultLcmUrl in sim_server/bus/channels.hpp (the C++ definition): keep them
% equal.
k.DEFAULT_URL = 'udpm://239.255.76.67:7667?ttl=0&recv_buf_size=4194304';
% The exit codes of sim_server/common/exit_code.hpp (docs/exit_codes.md).
k.EXIT_OK = 0;
k.EXIT_ERROR = 1;
k.EXIT_NOT_CONVERGED = 2;
k.EXIT_TIMEOUT = 4;
k.EXIT_REJECTED = 5;
k.SLICE_MS = 50;            % longest single wait on the bus
k.DESCRIBE_AFTER_MS = 250;  % ask for the model when it has not come by then
% The largest model and state taken [bytes], as sim_server/bus/receive_limits.hpp states them
% (kModelLimit, kStateLimitBeforeModel, kRejectionLimit).
k.MODEL_LIMIT = 64 * 1024 * 1024;
k.STATE_LIMIT = 32 * 1024 * 1024;
k.REJECTION_LIMIT = 8192;
% Characters of a notice's reason shown (a sentence naming a muscle and a step).
k.REASON_SHOWN = 300;
% --option=value; MUSCLE=LEVEL[@WINDOW]; START[:END]; a decimal number (whole strings).
k.OPTION_WITH_VALUE = '^(--[A-Za-z0-9-]+)=(.*)$';
k.ENTRY = '^([^=]+)=([^@]+)@?(.*)$';
k.WINDOW = '^([^:]+):?(.*)$';
k.NUMBER = '^[+-]?([0-9]+[.]?[0-9]*|[.][0-9]+)([eE][+-]?[0-9]+)?$';
end

% Ends the program with status, text on stderr (thrown through to step_controller).
function fail(status, text)
throw(MException(sprintf('step_controller:exit%d', status), '%s', text));
end

% Received text as a report prints it: characters outside printable ASCII as \xNN, cut at
% max_shown.
function shown = printable(text, max_shown)
shown = '';
for i = 1:min(numel(text), max_shown)
  c = text(i);
  if c >= 32 && c <= 126
    shown = [shown c]; %#ok<AGROW>
  else
    shown = [shown sprintf('\\x%02x', double(c))]; %#ok<AGROW>
  end
end
if numel(text) > max_shown, shown = sprintf('%s...(%d bytes)', shown, numel(text)); end
end

function usage_error(text)
k = constants();
fail(k.EXIT_ERROR, sprintf('%s\n%s', text, k.USAGE));
end

% A decimal number from text, or NaN.
function value = number(text)
k = constants();
if isempty(regexp(text, k.NUMBER, 'once'))
  value = NaN;
else
  value = str2double(text);
end
end

% A whole number >= minimum from text, or -1.
function value = whole_number(text, minimum)
value = number(text);
if ~(value == floor(value) && value >= minimum && value <= 2^53), value = -1; end
end

function entry = parse_entry(text)
k = constants();
parts = regexp(text, k.ENTRY, 'tokens', 'once');
if isempty(parts), usage_error(['''' text ''' is not MUSCLE=LEVEL[@START[:END]]']); end
entry = struct('name', parts{1}, 'level', number(parts{2}), 'start', 0, 'finish', Inf);
if ~(entry.level >= 0 && entry.level <= 1)
  usage_error(['''' text ''': the level must be a number in [0, 1]']);
end
window = parts{3};
if ~isempty(window)
  times = regexp(window, k.WINDOW, 'tokens', 'once');
  if isempty(times), entry.start = NaN; else, entry.start = number(times{1}); end
  if ~(entry.start >= 0), usage_error(['''' text ''': START must be a time >= 0 s']); end
  if ~isempty(times{2})
    entry.finish = number(times{2});
    if ~(entry.finish > entry.start)
      usage_error(['''' text ''': END must be a time > START (s)']);
    end
  end
end
end

% The options, or [] after --help.
function options = parse_arguments(args)
k = constants();
options.url = k.DEFAULT_URL;
options.prefix = 'TONGUE_';
options.max_steps = -1;  % none
options.timeout_ms = 10000;
options.entries = struct('name', {}, 'level', {}, 'start', {}, 'finish', {});
i = 1;
while i <= numel(args)
  arg = args{i};
  pair = regexp(arg, k.OPTION_WITH_VALUE, 'tokens', 'once');
  paired = ~isempty(pair);
  if paired, key = pair{1}; value = pair{2}; else, key = arg; value = []; end
  takes_value = any(strcmp(key, {'--lcm-url', '--prefix', '--max-steps', '--timeout-ms'}));
  if takes_value && ~paired
    i = i + 1;
    if i > numel(args), usage_error([key ' needs a value']); end
    value = args{i};
  end
  if strcmp(key, '--help') || strcmp(key, '-h')
    fprintf('%s\n', k.USAGE);
    options = [];
    return;
  elseif strcmp(key, '--lcm-url')
    options.url = value;
  elseif strcmp(key, '--prefix')
    options.prefix = value;
    if isempty(regexp(options.prefix, '^[A-Z0-9_]*$', 'once'))
      usage_error(['--prefix must contain only A-Z, 0-9 and _, not ''' options.prefix '''']);
    end
  elseif strcmp(key, '--max-steps')
    options.max_steps = whole_number(value, 1);
    if options.max_steps < 0, usage_error('--max-steps must be an integer >= 1'); end
  elseif strcmp(key, '--timeout-ms')
    options.timeout_ms = whole_number(value, 1);
    if options.timeout_ms < 0, usage_error('--timeout-ms must be an integer >= 1'); end
  elseif startsWith(arg, '-')
    usage_error(['unknown option ''' arg '''']);
  else
    options.entries(end + 1) = parse_entry(arg);
  end
  i = i + 1;
end
if isempty(options.entries), usage_error('no MUSCLE=LEVEL given'); end
end

% The muscles the entries name, each once, in the order of their first entry.
function names = named_muscles(entries)
names = {};
for i = 1:numel(entries)
  if ~any(strcmp(names, entries(i).name)), names{end + 1} = entries(i).name; end %#ok<AGROW>
end
end

% The level of muscle for the step that starts at time t (s), steps dt (s) long.
function level = level_at(entries, muscle, t, dt)
level = 0;
for i = 1:numel(entries)
  entry = entries(i);
  if strcmp(entry.name, muscle) && t >= entry.start - dt / 2 && t < entry.finish - dt / 2
    level = entry.level;
  end
end
end

% One LCM instance per URL, opened once and kept: LCM 1.3.1's close() joins its reader thread,
% which on Java 8 (MATLAB's) waits in a receive until a datagram comes, possibly for ever. The
% reader is a daemon thread; a MATLAB session that runs the controller again reuses the bus.
function bus = bus_at(url)
persistent buses
if isempty(buses), buses = containers.Map(); end
if ~isKey(buses, url)
  try
    % The constructor takes String... (providers): MATLAB passes a Java array.
    providers = javaArray('java.lang.String', 1);
    providers(1) = java.lang.String(url);
    buses(url) = lcm.lcm.LCM(providers);
  catch cause
    k = constants();
    fail(k.EXIT_ERROR, sprintf('cannot open the LCM bus at ''%s'': %s', url, cause.message));
  end
end
bus = buses(url);
end

% A Java String[] of a cell array of text (Java: names.toArray(new String[0])).
function strings = java_strings(texts)
strings = javaArray('java.lang.String', numel(texts));
for i = 1:numel(texts)
  strings(i) = java.lang.String(texts{i});
end
end

function bytes = encode(msg)
out = lcm.lcm.LCMDataOutputStream();
msg.encode(out);
bytes = out.toByteArray();
end

function unsubscribe(bus, channels, aggregator)
for i = 1:numel(channels)
  bus.unsubscribe(channels{i}, aggregator);
end
end
