// The page: reads the URL parameters and the session, loads the model(s), runs replay or live,
// draws each frame in both views and the panel, and exposes window.tongueViewer.
(function () {
  "use strict";

  function $(id) { return document.getElementById(id); }

  var CHOICES = {
    view: ["both", "3d", "2d"],
    field: ["muscle", "activation", "displacement"],
    camera: ["left", "front", "top", "oblique"],
    panel: ["1", "0"]
  };
  var params = new URLSearchParams(location.search);
  function choice(name, value) {
    value = value === undefined || value === null ? null : String(value);
    return CHOICES[name].indexOf(value) >= 0 ? value : null;
  }
  var settings = {
    view: choice("view", params.get("view")) || "both",
    field: choice("field", params.get("field")) || "muscle",
    camera: choice("camera", params.get("camera")) || "left",
    panel: choice("panel", params.get("panel")) || "1",
    side: params.get("compare") === "side"
  };

  var panel = new Panel();
  var view3d = null, view2d = null;
  var state = {
    mode: null,
    runs: [],              // session runs (replay)
    models: [],            // prepared models, one per run
    frames: [],            // the frames drawn, one per run
    framesDrawn: 0,
    modelVersion: null,
    error: null,           // the last error shown, cleared by the next good frame
    fault: null            // a lasting problem of the page itself (no 3D view), shown with every status
  };

  var readyResolve, readyReject;
  var ready = new Promise(function (res, rej) { readyResolve = res; readyReject = rej; });
  ready.catch(function () {});          // a failure is shown in the status line; awaiting it still sees it

  function showError(err) {
    var text = err && err.message ? err.message : String(err);
    state.error = text;
    panel.setStatus(text, "error");
    if (window.console) console.warn("tongue_viewer:", text);
  }

  // ---- layout ----------------------------------------------------------------------------

  function applyLayout() {
    document.body.classList.toggle("only-3d", settings.view === "3d");
    document.body.classList.toggle("only-2d", settings.view === "2d");
    document.body.classList.toggle("no-panel", settings.panel === "0");
    $("field").value = settings.field;
    $("camera").value = settings.camera;
    if (view3d) view3d.resize();
    if (view2d) view2d.resize();
  }

  function setupViews() {
    try {
      if (typeof THREE === "undefined" || !THREE.OrbitControls) throw new Error("three.js did not load from /three/");
      view3d = new Surface3D.View3D($("pane3d"), $("view3d"), $("legend"));
    } catch (e) {
      // the page goes on with the 2D view; the reason stays in the 3D pane and the status line
      state.fault = "no 3D view: " + (/WebGL/i.test(e.message) ? "WebGL is not available" : e.message);
      $("legend").textContent = state.fault;
      $("legend").className = "fault";
      showError(new Error(state.fault));
      view3d = null;
    }
    view2d = new Midsagittal.View2D($("pane2d"), $("view2d"));
    window.addEventListener("resize", function () {
      if (view3d) view3d.resize();
      view2d.resize();
    });
    $("field").addEventListener("change", function () { setView({ field: $("field").value }); });
    $("camera").addEventListener("change", function () { setView({ camera: $("camera").value }); });
    $("fibres").addEventListener("change", function () { redraw(); });
    applyLayout();
  }

  function setModels(models, names) {
    state.models = models;
    state.frames = [];
    if (view3d) view3d.setModels(models, settings.side, names);
    view2d.setModels(models, settings.side, names);
    if (view3d) view3d.setCamera(settings.camera);
    panel.setMuscles(models[0].muscles, models.length > 1 ? models[1].muscles : null);
  }

  // ---- drawing ---------------------------------------------------------------------------

  // Frames are drawn on the next animation frame; the newest one per run wins.
  var toDraw = null, drawWaiters = [], afterDraw = null;
  function draw(frames) {
    toDraw = toDraw || [];
    frames.forEach(function (f, r) { if (f) toDraw[r] = f; });
    var p = new Promise(function (resolve) { drawWaiters.push(resolve); });
    if (drawWaiters.length === 1) requestAnimationFrame(drawNow);
    return p;
  }
  function redraw() { return draw(state.frames.slice()); }

  function drawNow() {
    var frames = toDraw || [], waiters = drawWaiters;
    toDraw = null; drawWaiters = [];
    // a redraw (new view, field, fibres) shows the same frames: not counted, status kept
    var fresh = frames.some(function (f, r) { return f && f !== state.frames[r]; });
    frames.forEach(function (f, r) { if (f) state.frames[r] = f; });
    var shown = state.frames;
    try {
      if (shown[0]) {
        if (view3d) view3d.update(shown, settings.field, $("fibres").checked);
        view2d.update(shown);
        panel.update(shown[0], shown[1]);
        if (fresh) {
          showFrameStatus(shown[0]);
          state.framesDrawn++;
          if (state.framesDrawn === 1) readyResolve();
        }
      }
    } catch (e) {
      showError(e);
    }
    waiters.forEach(function (w) { w(); });
    if (afterDraw) afterDraw();
  }

  function showFrameStatus(f) {
    var parts = [state.mode === "live" ? "live" : "replay", f.status || "ok"];
    if (!f.converged) parts.push("not converged");
    if (f.contactNodes.length) parts.push(f.contactNodes.length + (f.contactNodes.length === 1 ? " node" : " nodes") + " in contact, max penetration " + (f.maxPenetration * 1000).toFixed(2) + " mm");
    if (f.reducedCorrection > 0) parts.push("reduced model: correction " + (f.reducedCorrection * 1000).toFixed(3) + " mm");
    if (state.mode === "live" && f.dropped) parts.push(f.dropped + (f.dropped === 1 ? " state" : " states") + " not shown");
    state.error = null;
    // a frame drawn after the connection dropped must not hide that it did
    if (state.mode === "live" && !live.socket.connected()) state.error = "connection to the server lost; retrying every 2 s";
    var problem = [state.error, state.fault].filter(Boolean).join(" · ");
    if (problem) { panel.setStatus(parts.join(" · ") + " · " + problem, "error"); return; }
    panel.setStatus(parts.join(" · "), (f.status && f.status !== "ok") || !f.converged ? "warn" : "ok");
  }

  // ---- replay ----------------------------------------------------------------------------

  var replay = null;

  function startReplay(session) {
    state.runs = (session.runs || []).slice(0, 2);   // a run and its reference: the page shows two
    if (!state.runs.length) throw new Error("/api/session: replay without runs");
    state.runs.forEach(function (r, i) {
      if (!Array.isArray(r.times) || !r.times.length) throw new Error("/api/session: run " + i + " (" + r.name + ") has no frames");
    });
    panel.setAnalysis(state.runs[0].analysis);
    var names = state.runs.map(function (r) { return r.name; });
    // models one after the other: one request in flight
    var models = [];
    return state.runs.reduce(function (chain, run, r) {
      return chain.then(function () {
        return TongueApi.model(r).then(function (json) {
          try {
            models.push(TongueModel.prepare(json));
          } catch (e) {
            throw new Error("/api/model?run=" + r + " (" + run.name + "): " + e.message);
          }
        }).catch(function (err) {
          if (r === 0) throw err;
          showError(new Error("run 1 (" + run.name + ") left out: " + err.message));
        });
      });
    }, Promise.resolve()).then(function () {
      state.runs = state.runs.slice(0, models.length);
      state.modelVersion = models[0].version;
      setModels(models, names.slice(0, models.length));
      replay = new Replay(state.runs, loadReplayFrames, showError);
      var t = params.has("time") ? Number(params.get("time")) : replay.t0;
      return replay.want(t);
    });
  }

  // Fetch the frames at these indices (only those not already shown), one request at a time,
  // then draw them together.
  function loadReplayFrames(indices) {
    var got = [];
    return indices.reduce(function (chain, index, r) {
      return chain.then(function () {
        var shown = state.frames[r];
        if (shown && shown.index === index) return;
        return TongueApi.frame(r, index).then(function (json) {
          try {
            got[r] = TongueModel.readFrame(state.models[r], json, null);
          } catch (e) {
            throw new Error("run " + r + ", frame " + index + ": " + e.message);
          }
          got[r].index = index;
        });
      });
    }, Promise.resolve()).then(function () { return draw(got); });
  }

  // ---- live ------------------------------------------------------------------------------

  var live = { socket: null, loading: false, again: false, pending: null, retry: null };

  function startLive() {
    $("replay").hidden = true;
    live.socket = new TongueApi.LiveSocket({
      onOpen: function () { live.socket.next(); },   // just connected: ask for the newest state
      onHello: function (msg) {
        if (msg.model_version === null || msg.model_version === undefined) {
          panel.setStatus("connected; waiting for a model from the simulation", "warn");
        } else {
          loadLiveModel();              // (again after a reconnect: the server may have restarted)
        }
      },
      onModel: function () { loadLiveModel(); },
      onStatus: function (text) { panel.setStatus(text, "warn"); },
      onFrame: liveFrame,
      onClose: function (why) { showError(new Error(why)); }
    });
    afterDraw = function () { live.socket.next(); };
  }

  function loadLiveModel() {
    if (live.loading) { live.again = true; return; }
    live.loading = true;
    clearTimeout(live.retry);
    TongueApi.model().then(function (json) {
      var m = TongueModel.prepare(json);
      state.modelVersion = m.version;
      // a reconnect to the same model keeps the views (and the trails)
      if (!sameModel(state.models[0], m)) setModels([m], null);
    }).catch(function (err) {
      showError(err);
      live.retry = setTimeout(loadLiveModel, 2000);   // e.g. 404 before the model arrived
    }).then(function () {
      live.loading = false;
      if (live.again) { live.again = false; loadLiveModel(); return; }
      if (live.pending) { var f = live.pending; live.pending = null; liveFrame(f); }
    });
  }

  function sameModel(a, b) {
    if (!a || a.version !== b.version || a.numNodes !== b.numNodes) return false;
    if (a.surfaceTriangles.length !== b.surfaceTriangles.length || a.obstacles.length !== b.obstacles.length) return false;
    for (var i = 0; i < a.rest.length; i++) if (a.rest[i] !== b.rest[i]) return false;
    return a.muscles.map(function (x) { return x.name; }).join() === b.muscles.map(function (x) { return x.name; }).join();
  }

  function liveFrame(msg) {
    if (live.loading || !state.models.length) { live.pending = msg; return; }   // drawn once the model is in
    var frame;
    try {
      frame = TongueModel.readFrame(state.models[0], msg, state.frames[0] && state.frames[0].positions);
    } catch (e) {
      showError(e);
      live.socket.next();               // skip it; a new model may be on its way
      return;
    }
    draw([frame]);                      // afterDraw sends "next"
  }

  // ---- the API ---------------------------------------------------------------------------

  function setView(opts) {
    opts = opts || {};
    ["view", "field", "camera"].forEach(function (k) {
      var v = choice(k, opts[k]);
      if (v) settings[k] = v;
    });
    if (opts.panel !== undefined) {
      var p = choice("panel", opts.panel === true ? 1 : opts.panel === false ? 0 : opts.panel);
      if (p) settings.panel = p;
    }
    applyLayout();
    if (view3d && opts.camera) view3d.setCamera(settings.camera);
    return redraw();
  }

  window.tongueViewer = {
    ready: ready,
    info: function () {
      var f = state.frames[0];
      return { mode: state.mode, run: 0, index: f ? (state.mode === "live" ? null : f.index) : null,
               step: f ? f.step : null, time: f ? f.time : null,
               framesDrawn: state.framesDrawn, modelVersion: state.modelVersion };
    },
    positions: function (run) {
      var f = state.frames[run || 0];
      return f ? Array.prototype.slice.call(f.positions) : null;
    },
    seek: function (time) {
      if (!replay) return Promise.reject(new Error("seek: only in replay mode"));
      return replay.want(Number(time));
    },
    setView: setView
  };

  // ---- start -----------------------------------------------------------------------------

  // The session first (retried every 2 s until the server answers), then replay or live.
  function start() {
    panel.setStatus("loading the session…", "warn");
    TongueApi.session().then(begin, function (err) {
      showError(new Error(err.message + "; retrying every 2 s"));
      setTimeout(start, 2000);
    });
  }

  function begin(session) {
    state.mode = session.mode;
    $("mode").textContent = session.mode === "live"
      ? "live · " + (session.bus || "") + " " + (session.prefix || "")
      : "replay · " + (session.runs || []).map(function (r) { return r.name + " (" + r.status + ")"; }).join(" vs ");
    Promise.resolve().then(function () {
      if (session.mode === "live") return startLive();
      if (session.mode === "replay") return startReplay(session);
      throw new Error("/api/session: unknown mode " + JSON.stringify(session.mode));
    }).catch(function (err) {
      showError(err);
      readyReject(err);
    });
  }

  setupViews();
  start();
})();
