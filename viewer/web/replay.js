// Replay controls: the time slider, play/pause, speed, the frame label, and the frame requests.
// Only the newest wanted time is kept and a new request leaves only once the previous frames
// are drawn, so a slow server or page drops frames rather than queueing them.
var Replay = (function () {
  "use strict";

  function $(id) { return document.getElementById(id); }

  // index of the time in times (sorted) nearest t
  function nearest(times, t) {
    var lo = 0, hi = times.length - 1;
    if (hi < 0) return -1;
    while (hi - lo > 1) {
      var mid = (lo + hi) >> 1;
      if (times[mid] <= t) lo = mid; else hi = mid;
    }
    return Math.abs(times[hi] - t) < Math.abs(times[lo] - t) ? hi : lo;
  }

  // runs: the session's runs; load(indices) fetches and draws those frames (one per run) and
  // returns a Promise resolved once they are drawn; onError(err) reports a failed load.
  function Replay(runs, load, onError) {
    this.runs = runs;
    this.load = load;
    this.onError = onError;
    this.t0 = Math.min.apply(null, runs.map(function (r) { return r.times.length ? r.times[0] : 0; }));
    this.t1 = Math.max.apply(null, runs.map(function (r) { return r.times.length ? r.times[r.times.length - 1] : 0; }));
    this.time = this.t0;
    this.playing = false;
    this.shown = null;                  // indices drawn, one per run
    this.inFlight = false;
    this.seq = 0;                       // number of the newest wanted time
    this.waiters = [];                  // {seq, resolve, reject}

    var self = this, slider = $("slider");
    slider.min = this.t0; slider.max = this.t1; slider.step = "any"; slider.value = this.t0;
    slider.addEventListener("input", function () { self.want(Number(slider.value)).catch(function () {}); });
    $("play").addEventListener("click", function () { self.setPlaying(!self.playing); });
    // space plays and pauses, unless a form control has the keyboard
    document.addEventListener("keydown", function (ev) {
      if (ev.key !== " " || /^(INPUT|SELECT|BUTTON|TEXTAREA)$/.test(document.activeElement.tagName)) return;
      ev.preventDefault();
      self.setPlaying(!self.playing);
    });
    $("replay").hidden = false;
  }

  Replay.prototype.indicesAt = function (t) {
    return this.runs.map(function (r) { return nearest(r.times, t); });
  };

  // Show each run's frame nearest t; resolved once drawn (or once a later wanted time is drawn).
  Replay.prototype.want = function (t) {
    if (!isFinite(t)) t = this.t0;
    this.time = Math.max(this.t0, Math.min(this.t1, t));
    var seq = ++this.seq, self = this;
    var p = new Promise(function (resolve, reject) { self.waiters.push({ seq: seq, resolve: resolve, reject: reject }); });
    this.pump();
    return p;
  };

  Replay.prototype.settle = function (seq, err) {
    this.waiters = this.waiters.filter(function (w) {
      if (w.seq > seq) return true;
      if (err) w.reject(err); else w.resolve();
      return false;
    });
  };

  Replay.prototype.pump = function () {
    if (this.inFlight) return;          // the draw in flight calls pump again
    var seq = this.seq, idx = this.indicesAt(this.time), self = this;
    this.showTime();
    if (this.shown && idx.every(function (v, r) { return v === self.shown[r]; })) { this.settle(seq); return; }
    this.inFlight = true;
    this.load(idx).then(function () {
      self.shown = idx;
      self.settle(seq);
    }, function (err) {
      self.settle(seq, err);
      self.setPlaying(false);
      self.onError(err);
    }).then(function () {
      self.inFlight = false;
      if (self.seq !== seq && self.waiters.length) self.pump();
    });
  };

  Replay.prototype.showTime = function () {
    $("slider").value = this.time;
    var idx = this.indicesAt(this.time), runs = this.runs;
    $("frame").textContent = idx.map(function (i, r) {
      return (runs.length > 1 ? "run " + r + ": " : "") + "frame " + i + " / " + (runs[r].frames - 1);
    }).join(" · ");
  };

  Replay.prototype.setPlaying = function (on) {
    if (on === this.playing) return;
    this.playing = on;
    $("play").textContent = on ? "❚❚ pause" : "▶ play";
    if (!on) return;
    if (this.time >= this.t1) this.time = this.t0;   // play at the end starts again
    var self = this, last = performance.now();
    function tick(now) {
      if (!self.playing) return;
      var speed = Number($("speed").value) || 1;
      var t = self.time + (now - last) / 1000 * speed;
      last = now;
      if (t >= self.t1) { t = self.t1; self.setPlaying(false); }
      self.want(t).catch(function () {});
      if (self.playing) requestAnimationFrame(tick);
    }
    requestAnimationFrame(tick);
  };

  return Replay;
})();
