// Talking to tongue_viewer: the HTTP endpoints (session, model, frame) and the live WebSocket
// with its "next" flow control. Every failure becomes an Error whose message can go straight
// into the status line.
var TongueApi = (function () {
  "use strict";

  var TIMEOUT_MS = 10000;   // a hung request would otherwise stall the one-frame-in-flight chain
  var RECONNECT_MS = 2000;

  function getJSON(path) {
    var abort = new AbortController();
    var timer = setTimeout(function () { abort.abort(); }, TIMEOUT_MS);
    return fetch(path, { cache: "no-store", signal: abort.signal })
      .catch(function (e) {
        throw new Error(e.name === "AbortError" ? "no answer to " + path + " within " + TIMEOUT_MS / 1000 + " s"
                                                : "server unreachable (" + path + ")");
      })
      .then(function (res) {
        return res.text().then(function (text) {
          var body = null;
          try { body = JSON.parse(text); } catch (e) { /* reported below */ }
          if (!res.ok) {
            var why = body && body.error ? body.error : text.slice(0, 200) || res.statusText;
            var err = new Error(path + ": HTTP " + res.status + ": " + why);
            err.status = res.status;
            throw err;
          }
          if (body === null || typeof body !== "object") throw new Error(path + ": not a JSON object");
          return body;
        });
      })
      .finally(function () { clearTimeout(timer); });
  }

  function session() { return getJSON("/api/session"); }
  // run is undefined in live mode (the server has one model), 0 or 1 in replay
  function model(run) { return getJSON(run === undefined ? "/api/model" : "/api/model?run=" + run); }
  function frame(run, index) { return getJSON("/api/frame?run=" + run + "&index=" + index); }

  // The live connection. handlers: onHello(msg), onModel(msg), onStatus(text), onFrame(frame),
  // onOpen(), onClose(text). The owner calls next() once it has drawn a frame (or is ready for
  // the first); at most one "next" is outstanding, so at most one frame is in flight.
  function LiveSocket(handlers) {
    this.handlers = handlers;
    this.ws = null;
    this.waiting = false;      // a "next" was sent and its frame has not arrived
    this.stopped = false;
    this.connect();
  }

  LiveSocket.prototype.connect = function () {
    var self = this, h = this.handlers;
    var url = (location.protocol === "https:" ? "wss://" : "ws://") + location.host + "/ws";
    var ws;
    try { ws = new WebSocket(url); } catch (e) { this.retry("cannot open " + url); return; }
    this.ws = ws;
    this.waiting = false;
    ws.onopen = function () { if (h.onOpen) h.onOpen(); };
    ws.onmessage = function (ev) {
      var msg;
      try { msg = JSON.parse(ev.data); } catch (e) { h.onStatus("bad message from the server (not JSON)", "error"); return; }
      if (!msg || typeof msg !== "object") return;
      if (msg.type === "hello") h.onHello(msg);
      else if (msg.type === "model") h.onModel(msg);
      else if (msg.type === "status") h.onStatus(String(msg.text), "warn");
      else if (msg.type === "frame") { self.waiting = false; h.onFrame(msg); }
    };
    ws.onclose = function () {
      if (self.ws !== ws) return;
      self.ws = null;
      self.retry("connection to the server lost");
    };
    // onerror is always followed by onclose, which reports it
  };

  LiveSocket.prototype.retry = function (why) {
    if (this.stopped) return;
    if (this.handlers.onClose) this.handlers.onClose(why + "; retrying every " + RECONNECT_MS / 1000 + " s");
    var self = this;
    setTimeout(function () { self.connect(); }, RECONNECT_MS);
  };

  LiveSocket.prototype.connected = function () {
    return !!this.ws && this.ws.readyState === WebSocket.OPEN;
  };

  LiveSocket.prototype.next = function () {
    if (this.waiting || !this.ws || this.ws.readyState !== WebSocket.OPEN) return;
    this.waiting = true;
    this.ws.send(JSON.stringify({ type: "next" }));
  };

  return { session: session, model: model, frame: frame, LiveSocket: LiveSocket };
})();
