// The 2D view: the section of the boundary surface by the midsagittal plane z = mid z of the
// rest bounding box, drawn on a canvas in the x (anterior, to the right) / y (up) plane: the
// shape now, the rest shape dashed, the landmarks, the obstacles' sections, the contact nodes,
// and a mm scale bar. Fitted once per model so that the picture does not jump while it moves.
var Midsagittal = (function () {
  "use strict";

  var INK = "#1a1a2e", REST = "#8a8a8a", OBSTACLE = "#a0845c", CONTACT = "#e00000";

  // Segments [x1, y1, x2, y2, ...] where the triangles cut the plane z = z0. A vertex on the
  // plane counts as above it, so that a row of nodes on the plane gives each segment once.
  function section(xyz, tris, z0) {
    var out = [];
    var p = [0, 0, 0, 0];
    for (var t = 0; t < tris.length; t += 3) {
      var k = 0;
      for (var e = 0; e < 3; e++) {
        var a = tris[t + e], b = tris[t + (e + 1) % 3];
        var da = xyz[3 * a + 2] - z0, db = xyz[3 * b + 2] - z0;
        if ((da < 0) === (db < 0)) continue;
        var s = da / (da - db);
        if (k < 4) {
          p[k++] = xyz[3 * a] + s * (xyz[3 * b] - xyz[3 * a]);
          p[k++] = xyz[3 * a + 1] + s * (xyz[3 * b + 1] - xyz[3 * a + 1]);
        }
      }
      if (k === 4 && (p[0] !== p[2] || p[1] !== p[3])) out.push(p[0], p[1], p[2], p[3]);
    }
    return out;
  }

  function niceLength(v) {              // 1, 2, 5 x 10^k at or below v
    var p = Math.pow(10, Math.floor(Math.log10(v)));
    var m = v / p;
    return (m >= 5 ? 5 : m >= 2 ? 2 : 1) * p;
  }

  function View2D(container, canvas) {
    this.container = container;
    this.canvas = canvas;
    this.ctx = canvas.getContext("2d");
    this.runs = [];                     // {model, rest, obstacles: [segments]}
    this.frames = [];
    this.side = false;
    this.names = [];
  }

  View2D.prototype.setModels = function (models, side, names) {
    this.side = side && models.length > 1;
    this.names = names || [];
    this.frames = [];
    var xs = [], ys = [];
    this.runs = models.map(function (m, r) {
      var run = { model: m, rest: section(m.rest, m.surfaceTriangles, m.midZ), obstacles: [] };
      // each obstacle once per pane: overlaid runs of one scene share theirs
      var drawn = this.side || r === 0 ? [] : models[0].obstacles.map(function (o) { return o.name; });
      run.obstacles = m.obstacles.filter(function (o) { return drawn.indexOf(o.name) < 0; })
        .map(function (o) { return section(o.vertices, o.triangles, m.midZ); });
      [run.rest].concat(run.obstacles).forEach(function (segs) {
        for (var i = 0; i < segs.length; i += 2) { xs.push(segs[i]); ys.push(segs[i + 1]); }
      });
      return run;
    }, this);
    if (!xs.length) models.forEach(function (m) { xs.push(m.box.min[0], m.box.max[0]); ys.push(m.box.min[1], m.box.max[1]); });
    // room around the rest shape and the obstacles for where the tongue goes (~1 cm each side)
    var x0 = Math.min.apply(null, xs), x1 = Math.max.apply(null, xs), y0 = Math.min.apply(null, ys), y1 = Math.max.apply(null, ys);
    var pad = 0.12 * Math.max(x1 - x0, y1 - y0);
    this.fit = { x0: x0 - pad, x1: x1 + pad, y0: y0 - pad, y1: y1 + pad };
    this.resize();
  };

  View2D.prototype.update = function (frames) {
    for (var r = 0; r < frames.length; r++) if (frames[r]) this.frames[r] = frames[r];
    this.draw();
  };

  View2D.prototype.resize = function () {
    var dpr = window.devicePixelRatio || 1;
    this.width = Math.max(1, this.container.clientWidth);
    this.height = Math.max(1, this.container.clientHeight);
    this.canvas.width = Math.round(this.width * dpr);
    this.canvas.height = Math.round(this.height * dpr);
    this.ctx.setTransform(dpr, 0, 0, dpr, 0, 0);
    this.draw();
  };

  function strokeSegments(ctx, segs, tx, ty) {
    ctx.beginPath();
    for (var i = 0; i < segs.length; i += 4) {
      ctx.moveTo(tx(segs[i]), ty(segs[i + 1]));
      ctx.lineTo(tx(segs[i + 2]), ty(segs[i + 3]));
    }
    ctx.stroke();
  }

  function dot(ctx, x, y, r, colour) {
    ctx.fillStyle = colour;
    ctx.beginPath(); ctx.arc(x, y, r, 0, 2 * Math.PI); ctx.fill();
  }

  View2D.prototype.draw = function () {
    var ctx = this.ctx, W = this.width, H = this.height;
    ctx.clearRect(0, 0, W, H);
    ctx.fillStyle = "#fbfbf8"; ctx.fillRect(0, 0, W, H);
    if (!this.runs.length || !this.fit) return;
    if (!this.side) { this.drawPane(0, 0, 0, W, H); return; }
    // two runs side by side, or one above the other when the view is narrow
    if (W >= H) { this.drawPane(0, 0, 0, W / 2, H); this.drawPane(1, W / 2, 0, W / 2, H); }
    else { this.drawPane(0, 0, 0, W, H / 2); this.drawPane(1, 0, H / 2, W, H / 2); }
  };

  View2D.prototype.drawPane = function (pane, left, top, W, H) {
    var ctx = this.ctx, f = this.fit, margin = 24;
    var scale = Math.min((W - 2 * margin) / (f.x1 - f.x0 || 1e-3), (H - 2 * margin - 28) / (f.y1 - f.y0 || 1e-3));
    var ox = left + (W - scale * (f.x1 - f.x0)) / 2, oy = top + margin + 4 + (H - 2 * margin - 28 - scale * (f.y1 - f.y0)) / 2;
    function tx(x) { return ox + (x - f.x0) * scale; }
    function ty(y) { return oy + (f.y1 - y) * scale; }   // y up

    var runIdx = this.side ? [pane] : this.runs.map(function (_, i) { return i; });
    ctx.save();
    ctx.beginPath(); ctx.rect(left, top, W, H); ctx.clip();
    if (top > 0) { ctx.strokeStyle = "#ccc"; ctx.lineWidth = 1; ctx.beginPath(); ctx.moveTo(left, top + 0.5); ctx.lineTo(left + W, top + 0.5); ctx.stroke(); }
    ctx.lineJoin = ctx.lineCap = "round";

    runIdx.forEach(function (r) {
      var run = this.runs[r];
      ctx.lineWidth = 1.5; ctx.strokeStyle = OBSTACLE; ctx.setLineDash([]);
      run.obstacles.forEach(function (segs) { strokeSegments(ctx, segs, tx, ty); });
      if (r === runIdx[0]) {            // one rest outline per pane
        ctx.lineWidth = 1; ctx.strokeStyle = REST; ctx.setLineDash([5, 4]);
        strokeSegments(ctx, run.rest, tx, ty);
        ctx.setLineDash([]);
      }
    }, this);

    // the overlaid second run first, so the first run's ink stays on top
    runIdx.slice().reverse().forEach(function (r) {
      var run = this.runs[r], frame = this.frames[r], m = run.model;
      if (!frame) return;
      var overlay = !this.side && r > 0;
      var ink = overlay ? Colormap.css(Colormap.SECOND_RUN, 0.85) : INK;
      ctx.lineWidth = overlay ? 2.5 : 2; ctx.strokeStyle = ink;
      strokeSegments(ctx, section(frame.positions, m.surfaceTriangles, m.midZ), tx, ty);

      var x = frame.positions;
      var contact = overlay ? Colormap.css(Colormap.SECOND_RUN) : CONTACT;
      frame.contactNodes.forEach(function (n) { dot(ctx, tx(x[3 * n]), ty(x[3 * n + 1]), 2.5, contact); });
      ctx.font = "11px sans-serif";
      m.landmarks.forEach(function (l) {
        var px = tx(x[3 * l.node]), py = ty(x[3 * l.node + 1]);
        dot(ctx, px, py, 3, ink);
        if (!overlay) { ctx.fillStyle = "#333"; ctx.fillText(l.name, px + 5, py - 4); }
      });
    }, this);

    // mm scale bar, about a fifth of the pane
    var mm = niceLength((W / 5) / scale * 1000), len = mm / 1000 * scale;
    var bx = left + 14, by = top + H - 14;
    ctx.strokeStyle = "#222"; ctx.lineWidth = 2; ctx.setLineDash([]);
    ctx.beginPath(); ctx.moveTo(bx, by - 4); ctx.lineTo(bx, by); ctx.lineTo(bx + len, by); ctx.lineTo(bx + len, by - 4); ctx.stroke();
    ctx.fillStyle = "#222"; ctx.font = "12px sans-serif";
    ctx.fillText(mm + " mm", bx + len + 6, by);
    ctx.fillStyle = "#555";
    ctx.fillText("midsagittal z = " + (this.runs[runIdx[0]].model.midZ * 1000).toFixed(1) + " mm · anterior →", left + 10, top + 16);
    if (this.side && this.names[pane]) { ctx.fillStyle = "#222"; ctx.fillText(this.names[pane], left + 10, top + 32); }
    ctx.restore();
  };

  return { View2D: View2D, section: section };
})();
