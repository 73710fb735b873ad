/*
 * StepController.java: a lock-step controller for sim_server in Java 8, on LCM's Java bindings
 * (lcm.jar) and the tongue_lcm classes lcm-gen generates. It does what the Lua controller
 * (controllers/lua/step_controller.lua) does, option for option, and the MATLAB controller
 * (controllers/matlab/step_controller.m) is this program line for line: the same
 * MessageAggregator polling loop, so that what the Java program is tested to do, the MATLAB one
 * does too.
 *
 * usage: step_controller [--lcm-url URL] [--prefix TONGUE_] [--max-steps N]
 *                        [--timeout-ms MS] MUSCLE=LEVEL[@START[:END]] ...
 *
 * It reads the model (sent by the server at start; asked for with "describe" if it has not come
 * within 250 ms), checks that every MUSCLE is one of the model's, then answers each state k the
 * server publishes with the activation tagged k + 1: every muscle of the command line, each at its
 * level for step k + 1, in one message (muscles it does not name keep their levels in the server).
 * With --max-steps N it ends (exit 0) once the state of step N has arrived; otherwise it runs
 * until the server falls silent.
 *
 * MUSCLE=LEVEL        the muscle at LEVEL (a fraction of its maximum force, in [0, 1]) throughout;
 * MUSCLE=LEVEL@START  from time START (s) on, 0 before;
 * MUSCLE=LEVEL@START:END
 *                     from START until END (s), 0 outside.
 * Step k + 1 runs from the time t of state k to t + dt; a window [START, END) holds for the steps
 * that start in it, START and END rounded to the nearest step start (t >= START - dt/2 and
 * t < END - dt/2, dt from the model). Where several entries name one muscle, the last whose
 * window holds sets its level. LEVEL, START and END are decimal numbers (e.g. 0.125, 1e-3).
 *
 * --lcm-url URL    LCM provider (default udpm://239.255.76.67:7667?ttl=0&recv_buf_size=4194304;
 *                  LCM's Java udpm ignores recv_buf_size)
 * --prefix P       channel prefix of the server (default TONGUE_)
 * --max-steps N    stop after answering state N - 1 and seeing state N
 * --timeout-ms MS  give up (exit 4) when nothing comes from the server for MS ms (default 10000)
 *
 * Start it before the server, or after: a server already waiting is asked for its model, which
 * it sends with its current state. A state published again for a step already answered is
 * answered with the very bytes sent for it, which the server takes once. The activations name
 * their sender, "step_controller:<pid>"; a rejection notice of the server about the last one sent
 * ends the controller (exit 5) with its reason.
 *
 * Exit status: 0 state N reached; 1 a bad command line, a muscle not in the model, or LCM
 * failed; 2 a step failed to converge; 4 the server fell silent; 5 the server rejected the
 * activation. Run it with lcm.jar and tongue_lcm.jar on the class path: the build's wrapper
 * build/controllers/java/step_controller does that.
 */

import java.io.IOException;
import java.lang.management.ManagementFactory;
import java.math.BigDecimal;
import java.math.MathContext;
import java.util.ArrayList;
import java.util.Arrays;
import java.util.HashMap;
import java.util.LinkedList;
import java.util.List;
import java.util.Map;
import java.util.regex.Matcher;
import java.util.regex.Pattern;

import lcm.lcm.LCM;
import lcm.lcm.LCMDataOutputStream;
import lcm.lcm.MessageAggregator;
import tongue_lcm.lcmt_tongue_activation;
import tongue_lcm.lcmt_tongue_command;
import tongue_lcm.lcmt_tongue_model;
import tongue_lcm.lcmt_tongue_rejection;
import tongue_lcm.lcmt_tongue_state;

public final class StepController {
  static final String PROG = "step_controller";
  static final String USAGE = "usage: step_controller [--lcm-url URL] [--prefix TONGUE_] "
      + "[--max-steps N] [--timeout-ms MS] MUSCLE=LEVEL[@START[:END]] ...";
  // The same as kDefaultLcmUrl in sim_server/bus/channels.hpp (the C++ definition): keep them
  // equal.
  static final String DEFAULT_URL = "udpm://239.255.76.67:7667?ttl=0&recv_buf_size=4194304";
  // The exit codes of sim_server/common/exit_code.hpp (docs/exit_codes.md).
  static final int EXIT_OK = 0;
  static final int EXIT_ERROR = 1;
  static final int EXIT_NOT_CONVERGED = 2;
  static final int EXIT_TIMEOUT = 4;
  static final int EXIT_REJECTED = 5;
  static final int SLICE_MS = 50;            // longest single wait on the bus
  static final int DESCRIBE_AFTER_MS = 250;  // ask for the model when it has not come by then

  // The largest model and state taken [bytes], as sim_server/bus/receive_limits.hpp states them
  // (kModelLimit, kStateLimitBeforeModel, kRejectionLimit).
  static final int MODEL_LIMIT = 64 * 1024 * 1024;
  static final int STATE_LIMIT = 32 * 1024 * 1024;
  static final int REJECTION_LIMIT = 8192;
  // Characters of a notice's reason shown (a sentence naming a muscle and a step).
  static final int REASON_SHOWN = 300;

  // --option=value; MUSCLE=LEVEL[@WINDOW]; START[:END]; a decimal number (whole strings).
  static final Pattern OPTION_WITH_VALUE = Pattern.compile("(--[A-Za-z0-9-]+)=(.*)",
                                                           Pattern.DOTALL);
  static final Pattern ENTRY = Pattern.compile("([^=]+)=([^@]+)@?(.*)", Pattern.DOTALL);
  static final Pattern WINDOW = Pattern.compile("([^:]+):?(.*)", Pattern.DOTALL);
  static final Pattern NUMBER =
      Pattern.compile("[+-]?([0-9]+[.]?[0-9]*|[.][0-9]+)([eE][+-]?[0-9]+)?");

  // Ends the program with status, text on stderr (thrown through to main).
  static final class Failure extends RuntimeException {
    private static final long serialVersionUID = 1L;
    final int status;

    Failure(int status, String text) {
      super(text);
      this.status = status;
    }
  }

  // One MUSCLE=LEVEL[@START[:END]]; times in s.
  static final class Entry {
    String name;
    double level;
    double start = 0;
    double finish = Double.POSITIVE_INFINITY;
  }

  static final class Options {
    String url = DEFAULT_URL;
    String prefix = "TONGUE_";
    long maxSteps = -1;  // none
    long timeoutMs = 10000;
    List<Entry> entries = new ArrayList<>();
  }

  // A decoder of lcm-gen's classes: their constructor from bytes.
  interface Decoder<T> {
    T decode(byte[] data) throws IOException;
  }

  public static void main(String[] args) {
    int status;
    try {
      status = new StepController().drive(args);
    } catch (Failure failure) {
      System.err.println(PROG + ": " + failure.getMessage());
      status = failure.status;
    } catch (IOException | RuntimeException cause) {
      System.err.println(PROG + ": LCM failed: " + cause);
      status = EXIT_ERROR;
    }
    System.exit(status);
  }

  // Received text as a report prints it: characters outside printable ASCII as \xNN, cut at
  // maxShown.
  static String printable(String text, int maxShown) {
    StringBuilder shown = new StringBuilder();
    for (int i = 0; i < Math.min(text.length(), maxShown); ++i) {
      char c = text.charAt(i);
      if (c >= 32 && c <= 126) {
        shown.append(c);
      } else {
        shown.append(String.format("\\x%02x", (int) c));
      }
    }
    if (text.length() > maxShown) shown.append("...(" + text.length() + " bytes)");
    return shown.toString();
  }

  // x as C's printf "%.6g" writes it (Java's %g keeps trailing zeros).
  static String shortNumber(double x) {
    if (x == 0 || Double.isNaN(x) || Double.isInfinite(x)) return x == 0 ? "0" : Double.toString(x);
    BigDecimal rounded = new BigDecimal(x).round(new MathContext(6));
    int exponent = rounded.precision() - rounded.scale() - 1;
    if (exponent < -4 || exponent >= 6) {
      String mantissa = rounded.movePointLeft(exponent).stripTrailingZeros().toPlainString();
      return String.format("%se%s%02d", mantissa, exponent < 0 ? "-" : "+", Math.abs(exponent));
    }
    return rounded.stripTrailingZeros().toPlainString();
  }

  static Failure usageError(String text) {
    return new Failure(EXIT_ERROR, text + "\n" + USAGE);
  }

  // A decimal number from text, or NaN.
  static double number(String text) {
    return NUMBER.matcher(text).matches() ? Double.parseDouble(text) : Double.NaN;
  }

  // A whole number >= minimum from text, or -1.
  static long wholeNumber(String text, long minimum) {
    double value = number(text);
    if (!(value == Math.floor(value) && value >= minimum && value <= 9007199254740992.0)) return -1;
    return (long) value;
  }

  static Entry parseEntry(String text) {
    Matcher parts = ENTRY.matcher(text);
    if (!parts.matches()) throw usageError("'" + text + "' is not MUSCLE=LEVEL[@START[:END]]");
    Entry entry = new Entry();
    entry.name = parts.group(1);
    entry.level = number(parts.group(2));
    if (!(entry.level >= 0 && entry.level <= 1)) {
      throw usageError("'" + text + "': the level must be a number in [0, 1]");
    }
    String window = parts.group(3);
    if (!window.isEmpty()) {
      Matcher times = WINDOW.matcher(window);
      entry.start = times.matches() ? number(times.group(1)) : Double.NaN;
      if (!(entry.start >= 0)) throw usageError("'" + text + "': START must be a time >= 0 s");
      if (!times.group(2).isEmpty()) {
        entry.finish = number(times.group(2));
        if (!(entry.finish > entry.start)) {
          throw usageError("'" + text + "': END must be a time > START (s)");
        }
      }
    }
    return entry;
  }

  // The options, or null after --help.
  static Options parseArguments(String[] args) {
    Options options = new Options();
    for (int i = 0; i < args.length; ++i) {
      String arg = args[i];
      Matcher pair = OPTION_WITH_VALUE.matcher(arg);
      boolean paired = pair.matches();
      String key = paired ? pair.group(1) : arg;
      String value = paired ? pair.group(2) : null;
      boolean takesValue = Arrays.asList("--lcm-url", "--prefix", "--max-steps", "--timeout-ms")
                               .contains(key);
      if (takesValue && !paired) {
        i = i + 1;
        if (i >= args.length) throw usageError(key + " needs a value");
        value = args[i];
      }
      if (key.equals("--help") || key.equals("-h")) {
        System.out.println(USAGE);
        return null;
      } else if (key.equals("--lcm-url")) {
        options.url = value;
      } else if (key.equals("--prefix")) {
        options.prefix = value;
        if (!options.prefix.matches("[A-Z0-9_]*")) {
          throw usageError("--prefix must contain only A-Z, 0-9 and _, not '" + options.prefix
                           + "'");
        }
      } else if (key.equals("--max-steps")) {
        options.maxSteps = wholeNumber(value, 1);
        if (options.maxSteps < 0) throw usageError("--max-steps must be an integer >= 1");
      } else if (key.equals("--timeout-ms")) {
        options.timeoutMs = wholeNumber(value, 1);
        if (options.timeoutMs < 0) throw usageError("--timeout-ms must be an integer >= 1");
      } else if (arg.startsWith("-")) {
        throw usageError("unknown option '" + arg + "'");
      } else {
        options.entries.add(parseEntry(arg));
      }
    }
    if (options.entries.isEmpty()) throw usageError("no MUSCLE=LEVEL given");
    return options;
  }

  // The muscles the entries name, each once, in the order of their first entry.
  static List<String> namedMuscles(List<Entry> entries) {
    List<String> names = new ArrayList<>();
    for (Entry entry : entries) {
      if (!names.contains(entry.name)) names.add(entry.name);
    }
    return names;
  }

  // The level of muscle for the step that starts at time t (s), steps dt (s) long.
  static double levelAt(List<Entry> entries, String muscle, double t, double dt) {
    double level = 0;
    for (Entry entry : entries) {
      if (entry.name.equals(muscle) && t >= entry.start - dt / 2 && t < entry.finish - dt / 2) {
        level = entry.level;
      }
    }
    return level;
  }

  // One LCM instance per URL, opened once and kept: LCM 1.3.1's close() joins its reader thread,
  // which on Java 8 (MATLAB's) waits in a receive until a datagram comes, possibly for ever. The
  // reader is a daemon thread; a MATLAB session that runs the controller again reuses the bus.
  static final Map<String, LCM> buses = new HashMap<>();

  static LCM busAt(String url) {
    if (!buses.containsKey(url)) {
      try {
        // The constructor takes String... (providers): MATLAB passes a Java array, as here.
        buses.put(url, new LCM(new String[] {url}));
      } catch (IOException | RuntimeException cause) {
        throw new Failure(EXIT_ERROR, "cannot open the LCM bus at '" + url + "': " + cause);
      }
    }
    return buses.get(url);
  }

  static byte[] encode(lcmt_tongue_activation msg) throws IOException {
    LCMDataOutputStream out = new LCMDataOutputStream();
    msg.encode(out);
    return out.toByteArray();
  }

  // The bus and what has been received from it.
  Options options;
  String channelState;
  String channelModel;
  String channelRejection;
  String sender;
  MessageAggregator aggregator;
  lcmt_tongue_model model;
  LinkedList<lcmt_tongue_state> states = new LinkedList<>();  // received, not yet answered
  lcmt_tongue_activation sentMsg;  // the last activation sent, and its bytes
  byte[] sentBytes;
  long rejected = 0;
  long reportedAt = -1;

  // Any process on the bus can send on these channels: a message too large, or one lcm-gen's
  // decoder fails on, is counted and reported (at most once a second), never fatal.
  <T> T take(Decoder<T> decoder, byte[] data, int limit, String what) {
    String reason = "larger than the " + limit + "-byte limit";
    if (data.length <= limit) {
      try {
        return decoder.decode(data);
      } catch (IOException | RuntimeException | OutOfMemoryError cause) {
        // OutOfMemoryError: a forged array count asks for more than the heap; nothing was taken.
        reason = cause.toString();
      }
    }
    rejected = rejected + 1;
    long second = System.currentTimeMillis() / 1000;
    if (second != reportedAt) {
      reportedAt = second;
      System.err.println(String.format("%s: rejected %s (%d so far): %s", PROG, what, rejected,
                                       printable(reason, 64)));
    }
    return null;
  }

  // Waits up to SLICE_MS for one message and handles it; false when none came.
  boolean handleNext() {
    MessageAggregator.Message message = aggregator.getNextMessage(SLICE_MS);
    if (message == null) return false;
    if (message.channel.equals(channelModel)) {
      lcmt_tongue_model received = take(lcmt_tongue_model::new, message.data, MODEL_LIMIT, "model");
      if (received != null) model = received;
    } else if (message.channel.equals(channelState)) {
      lcmt_tongue_state state = take(lcmt_tongue_state::new, message.data, STATE_LIMIT, "state");
      if (state != null) states.add(state);
    } else if (message.channel.equals(channelRejection)) {
      lcmt_tongue_rejection notice = take(lcmt_tongue_rejection::new, message.data,
                                          REJECTION_LIMIT, "rejection notice");
      if (notice != null && sentMsg != null && notice.sender.equals(sender)
          && notice.activation_step == sentMsg.step && notice.activation_utime == sentMsg.utime) {
        throw new Failure(EXIT_REJECTED, String.format(
            "the server rejected its activation for step %d (%s): %s: %s", notice.activation_step,
            sender, printable(notice.kind, 64), printable(notice.reason, REASON_SHOWN)));
      }
    }
    return true;
  }

  // Fails once nothing has come from the server for the timeout.
  void checkSilence(long silentMs, String what) {
    if (silentMs >= options.timeoutMs) {
      throw new Failure(EXIT_TIMEOUT, String.format(
          "nothing from the server on %s* for %d ms while waiting for %s", options.prefix,
          options.timeoutMs, what));
    }
  }

  int drive(String[] args) throws IOException {
    options = parseArguments(args);
    if (options == null) return EXIT_OK;
    List<String> names = namedMuscles(options.entries);
    String channelActivation = options.prefix + "ACTIVATION";
    channelState = options.prefix + "STATE";
    channelModel = options.prefix + "MODEL";
    String channelCommand = options.prefix + "COMMAND";
    channelRejection = options.prefix + "REJECTION";
    // The process id: the JVM's name is "<pid>@<host>" (Java 8 has no ProcessHandle).
    sender = PROG + ":" + ManagementFactory.getRuntimeMXBean().getName().split("@")[0];

    LCM bus = busAt(options.url);
    aggregator = new MessageAggregator();
    try {
      bus.subscribe(channelModel, aggregator);
      bus.subscribe(channelState, aggregator);
      bus.subscribe(channelRejection, aggregator);
      System.err.println(String.format("%s: listening on %s, channels %s*", PROG, options.url,
                                       options.prefix));

      long silentMs = 0;
      boolean described = false;
      while (model == null) {
        silentMs = handleNext() ? 0 : silentMs + SLICE_MS;
        if (!described && silentMs >= DESCRIBE_AFTER_MS) {
          lcmt_tongue_command command = new lcmt_tongue_command();
          command.utime = System.currentTimeMillis() * 1000;
          command.command = "describe";
          bus.publish(channelCommand, command);
          described = true;
        }
        checkSilence(silentMs, "the model");
      }
      List<String> known = Arrays.asList(model.muscle_names);
      for (String name : names) {
        if (!known.contains(name)) {
          throw new Failure(EXIT_ERROR, String.format(
              "muscle '%s' is not in the model (its muscles: %s)", name,
              String.join(", ", model.muscle_names)));
        }
      }
      double dt = model.dt;
      long answered = 0;
      lcmt_tongue_state state = null;

      while (true) {
        String what = state == null ? "the first state" : "the state of step " + (state.step + 1);
        silentMs = 0;
        while (states.isEmpty()) {
          silentMs = handleNext() ? 0 : silentMs + SLICE_MS;
          checkSilence(silentMs, what);
        }
        state = states.removeFirst();
        if (!state.converged) {
          throw new Failure(EXIT_NOT_CONVERGED, String.format(
              "the server reports step %d did not converge: %s", state.step + 1,
              printable(state.status, 64)));
        }
        if (options.maxSteps >= 0 && state.step >= options.maxSteps) break;
        if (sentMsg != null && sentMsg.step == state.step + 1) {
          // The step answered last, again ("paused", or repeated after a loss): the same bytes.
          bus.publish(channelActivation, sentBytes, 0, sentBytes.length);
        } else {
          lcmt_tongue_activation msg = new lcmt_tongue_activation();
          msg.utime = System.currentTimeMillis() * 1000;
          msg.step = state.step + 1;
          msg.num_muscles = names.size();
          msg.names = names.toArray(new String[0]);
          double[] levels = new double[names.size()];
          for (int i = 0; i < names.size(); ++i) {
            levels[i] = levelAt(options.entries, names.get(i), state.time, dt);
          }
          msg.levels = levels;
          msg.sender = sender;
          sentMsg = msg;
          sentBytes = encode(msg);
          bus.publish(channelActivation, sentBytes, 0, sentBytes.length);
          answered = answered + 1;
        }
      }
      System.err.println(String.format(
          "%s: answered %d states; reached step %d (t = %s s)%s", PROG, answered, state.step,
          shortNumber(state.time),
          rejected > 0 ? String.format("; %d messages rejected", rejected) : ""));
      return EXIT_OK;
    } finally {
      bus.unsubscribe(channelModel, aggregator);
      bus.unsubscribe(channelState, aggregator);
      bus.unsubscribe(channelRejection, aggregator);
    }
  }
}
