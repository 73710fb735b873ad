// The side panel: time (ms), step, real-time factor, Newton iterations, the status line, and one
// activation bar per muscle (a thinner second bar for the compared run, matched by name).
var Panel = (function () {
  "use strict";

  function $(id) { return document.getElementById(id); }

  function Panel() {
    this.rows = [];
    this.static = false;
    this.statusKind = "";
  }

  // muscles: of the first run; second: of the compared run or null
  Panel.prototype.setMuscles = function (muscles, second) {
    var box = $("activations");
    box.innerHTML = "";
    if (!muscles.length) box.textContent = "this model has no muscles";
    this.rows = muscles.map(function (m, i) {
      var row = document.createElement("div");
      row.className = "act-row";
      row.title = m.name + ": max force " + m.maxForce.toFixed(2) + " N";
      var label = document.createElement("span");
      label.className = "act-name"; label.textContent = m.name;
      var track = document.createElement("span");
      track.className = "act-track";
      var bar = document.createElement("span");
      bar.className = "act-bar"; bar.style.background = Colormap.css(m.colour);
      track.appendChild(bar);
      var bar2 = null, j = second ? second.map(function (s) { return s.name; }).indexOf(m.name) : -1;
      if (j >= 0) {
        bar2 = document.createElement("span");
        bar2.className = "act-bar act-bar-second"; bar2.style.background = Colormap.css(Colormap.SECOND_RUN);
        track.appendChild(bar2);
      }
      var value = document.createElement("span");
      value.className = "act-value";
      row.appendChild(label); row.appendChild(track); row.appendChild(value);
      box.appendChild(row);
      return { bar: bar, bar2: bar2, second: j, value: value, index: i };
    });
  };

  // analysis "static": the time axis is the load factor, not seconds
  Panel.prototype.setAnalysis = function (analysis) { this.static = analysis === "static"; };

  Panel.prototype.update = function (frame, second) {
    $("time").textContent = this.static ? "load " + frame.time.toFixed(3) : (frame.time * 1000).toFixed(1) + " ms";
    $("step").textContent = String(frame.step);
    $("rtf").textContent = frame.realTimeFactor === null ? "—" : frame.realTimeFactor.toFixed(frame.realTimeFactor < 10 ? 2 : 0) + "×";
    $("iterations").textContent = String(frame.iterations) + (frame.cuts ? " (" + frame.cuts + " cuts)" : "");
    $("iterations").title = "residual " + Number(frame.residual).toExponential(2) + " N";
    this.rows.forEach(function (r) {
      var a = frame.activations[r.index];
      r.bar.style.width = Math.max(0, Math.min(1, a)) * 100 + "%";
      r.value.textContent = a.toFixed(2);
      if (r.bar2) {
        var b = second ? second.activations[r.second] : 0;
        r.bar2.style.width = Math.max(0, Math.min(1, b)) * 100 + "%";
      }
    });
  };

  // kind: "ok", "warn" or "error" (styled; an error stays until something else replaces it)
  Panel.prototype.setStatus = function (text, kind) {
    var s = $("status");
    s.textContent = text;
    s.className = "status-" + (kind || "ok");
    this.statusKind = kind || "ok";
  };

  return Panel;
})();
