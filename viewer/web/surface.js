// The 3D view (three.js r111, global THREE): per run the boundary surface coloured by a field,
// the fibres, the landmarks with their trails, the contact points and forces; the obstacles;
// one camera with OrbitControls and presets. Two runs are overlaid in one scene or drawn side by
// side in two viewports of the one canvas. Scene units are metres, as in the data.
var Surface3D = (function () {
  "use strict";

  var TRAIL_SECONDS = 2;
  var TRAIL_POINTS = 1024;              // per landmark; the oldest points go first
  var ARROW_M_PER_N = 0.01;             // contact force arrows: 1 N is drawn 10 mm long
  var LANDMARK_RADIUS = 0.0012;         // m
  var FOV = 35;                         // degrees
  var CAMERAS = {                       // direction from the target to the camera
    left: [0, 0, 1],                    // from the subject's left (+z): anterior to the right
    front: [1, 0, 0],
    top: [-0.001, 1, 0],                // not exactly along "up", which OrbitControls cannot orbit from
    oblique: [0.75, 0.45, 0.85]
  };

  // the legend's top: the round number (1, 1.2, 1.5, 2, 2.5, 3, 4, 5, 6, 8 x 10^k) at or above v
  function niceCeil(v) {
    if (!(v > 0)) return 1;
    var p = Math.pow(10, Math.floor(Math.log10(v))), m = v / p;
    var steps = [1, 1.2, 1.5, 2, 2.5, 3, 4, 5, 6, 8, 10];
    for (var i = 0; i < steps.length; i++) if (m <= steps[i] * (1 + 1e-9)) return Number((steps[i] * p).toPrecision(3));
    return 10 * p;
  }

  function buffer(geometry, name, n, itemSize) {
    var a = new THREE.BufferAttribute(new Float32Array(n * itemSize), itemSize);
    a.setUsage ? a.setUsage(THREE.DynamicDrawUsage) : a.setDynamic(true);
    geometry.setAttribute(name, a);
    return a;
  }

  function obstacleMesh(o) {
    var g = new THREE.BufferGeometry();
    g.setAttribute("position", new THREE.BufferAttribute(new Float32Array(o.vertices), 3));
    g.setIndex(new THREE.BufferAttribute(o.triangles, 1));
    g.computeVertexNormals();
    var m = new THREE.Mesh(g, new THREE.MeshPhongMaterial({
      color: 0xd8c8a8, transparent: true, opacity: 0.28, depthWrite: false, side: THREE.DoubleSide }));
    m.renderOrder = 2;                  // after the tongue, so the tongue shows through
    return m;
  }

  // Everything drawn for one run. second: the compared run overlaid on the first (one colour,
  // translucent, no fibres) rather than a run of its own pane.
  function RunMesh(model, second) {
    this.model = model;
    this.second = second;
    this.group = new THREE.Group();
    var n = model.numNodes;

    var g = new THREE.BufferGeometry();
    this.position = buffer(g, "position", n, 3);
    this.colour = buffer(g, "color", n, 3);
    g.setIndex(new THREE.BufferAttribute(model.surfaceTriangles, 1));
    this.surfaceGeometry = g;
    var mat = second
      ? new THREE.MeshPhongMaterial({ color: new THREE.Color().fromArray(Colormap.SECOND_RUN), transparent: true,
                                      opacity: 0.15, depthWrite: false, side: THREE.DoubleSide, shininess: 10 })
      : new THREE.MeshPhongMaterial({ vertexColors: THREE.VertexColors, side: THREE.DoubleSide, shininess: 15,
                                      transparent: true, opacity: 1,
                                      polygonOffset: true, polygonOffsetFactor: 1, polygonOffsetUnits: 1 });
    this.surface = new THREE.Mesh(g, mat);
    this.surface.renderOrder = second ? 3 : 1;
    this.group.add(this.surface);
    if (second) {                       // a faint tint plus the quads' edges: the first run stays readable
      var eg = new THREE.BufferGeometry();
      eg.setAttribute("position", this.position);
      eg.setIndex(new THREE.BufferAttribute(model.surfaceEdges, 1));
      this.edges = new THREE.LineSegments(eg, new THREE.LineBasicMaterial({
        color: new THREE.Color().fromArray(Colormap.SECOND_RUN), transparent: true, opacity: 0.7 }));
      this.edges.frustumCulled = false;
      this.edges.renderOrder = 4;
      this.group.add(this.edges);
    }

    // fibres: one segment per pair of consecutive nodes, plus origin -> first node
    var f = model.fibres, segs = [];
    for (var i = 0; i + 1 < f.offsets.length; i++) {
      var a = f.offsets[i], b = f.offsets[i + 1];
      if (b <= a) continue;
      if (!isNaN(f.origins[3 * i])) segs.push([-1 - i, f.nodes[a], i]);    // negative: origin of fibre i
      for (var j = a; j + 1 < b; j++) segs.push([f.nodes[j], f.nodes[j + 1], i]);
    }
    this.fibreSegments = segs;
    if (!second && segs.length) {
      var fg = new THREE.BufferGeometry();
      this.fibrePosition = buffer(fg, "position", 2 * segs.length, 3);
      this.fibreColour = buffer(fg, "color", 2 * segs.length, 3);
      this.fibres = new THREE.LineSegments(fg, new THREE.LineBasicMaterial({ vertexColors: THREE.VertexColors }));
      this.group.add(this.fibres);
    }

    // landmarks and their trails
    var lmColour = second ? new THREE.Color().fromArray(Colormap.SECOND_RUN) : new THREE.Color(0x202020);
    var sphere = new THREE.SphereBufferGeometry(LANDMARK_RADIUS, 12, 8);
    this.landmarks = model.landmarks.map(function (l) {
      var s = new THREE.Mesh(sphere, new THREE.MeshPhongMaterial({ color: lmColour }));
      var tg = new THREE.BufferGeometry();
      var tp = buffer(tg, "position", TRAIL_POINTS, 3);
      tg.setDrawRange(0, 0);
      var trail = new THREE.Line(tg, new THREE.LineBasicMaterial({ color: lmColour, transparent: true, opacity: 0.8 }));
      trail.frustumCulled = false;      // its bounding sphere is not recomputed as it grows
      this.group.add(s); this.group.add(trail);
      return { node: l.node, sphere: s, trail: trail, trailPosition: tp, history: [] };
    }, this);

    // contact points and force arrows (grown on demand)
    var cg = new THREE.BufferGeometry();
    this.contactPosition = buffer(cg, "position", n, 3);
    cg.setDrawRange(0, 0);
    this.contactPoints = new THREE.Points(cg, new THREE.PointsMaterial({
      color: second ? 0xff8800 : 0xff0000, size: 5, sizeAttenuation: false, depthTest: false }));
    this.contactPoints.frustumCulled = false;
    this.contactPoints.renderOrder = 5;
    var ag = new THREE.BufferGeometry();
    this.arrowPosition = buffer(ag, "position", 2 * n, 3);
    ag.setDrawRange(0, 0);
    this.arrows = new THREE.LineSegments(ag, new THREE.LineBasicMaterial({ color: second ? 0xff8800 : 0xd00000, depthTest: false }));
    this.arrows.frustumCulled = false;
    this.arrows.renderOrder = 5;
    this.group.add(this.contactPoints); this.group.add(this.arrows);
  }

  // Per node: [level of the most active muscle through it, that muscle or -1]
  function mostActive(model, acts, node) {
    var list = model.nodeMuscles[node], best = -1, level = 0;
    for (var k = 0; k < list.length; k++) {
      var a = acts[list[k]];
      if (a > level) { level = a; best = list[k]; }
    }
    return [level, best];
  }

  RunMesh.prototype.update = function (frame, field, dispScale, showFibres) {
    var m = this.model, x = frame.positions, n = m.numNodes;
    var p = this.position.array, c = this.colour.array, rgb = [0, 0, 0];
    for (var i = 0; i < 3 * n; i++) p[i] = x[i];
    this.position.needsUpdate = true;
    this.surfaceGeometry.computeVertexNormals();
    this.surfaceGeometry.computeBoundingSphere();

    if (!this.second) {
      for (i = 0; i < n; i++) {
        var col;
        if (field === "displacement") {
          var dx = x[3 * i] - m.rest[3 * i], dy = x[3 * i + 1] - m.rest[3 * i + 1], dz = x[3 * i + 2] - m.rest[3 * i + 2];
          col = Colormap.map(Math.sqrt(dx * dx + dy * dy + dz * dz) * 1000 / dispScale, rgb);
        } else {
          var best = mostActive(m, frame.activations, i);
          if (field === "activation") col = Colormap.map(best[0], rgb);
          else col = best[0] > 1e-6 ? m.muscles[best[1]].colour : Colormap.GREY;
        }
        c[3 * i] = col[0]; c[3 * i + 1] = col[1]; c[3 * i + 2] = col[2];
      }
      this.colour.needsUpdate = true;
      // with fibres shown the surface becomes see-through, else they would be hidden inside
      var seeThrough = showFibres && !!this.fibres;
      this.surface.material.opacity = seeThrough ? 0.6 : 1;
      this.surface.material.depthWrite = !seeThrough;
    }

    if (this.fibres) {
      this.fibres.visible = showFibres;
      var fp = this.fibrePosition.array, fc = this.fibreColour.array, o = m.fibres.origins;
      this.fibreSegments.forEach(function (s, k) {
        var level = frame.activations[m.fibres.muscle[s[2]]];
        var colr = Colormap.map(level, rgb);
        for (var e = 0; e < 2; e++) {
          var node = s[e], at = 6 * k + 3 * e;
          if (node < 0) { var f = -1 - node; fp[at] = o[3 * f]; fp[at + 1] = o[3 * f + 1]; fp[at + 2] = o[3 * f + 2]; }
          else { fp[at] = x[3 * node]; fp[at + 1] = x[3 * node + 1]; fp[at + 2] = x[3 * node + 2]; }
          fc[at] = colr[0]; fc[at + 1] = colr[1]; fc[at + 2] = colr[2];
        }
      });
      this.fibrePosition.needsUpdate = true;
      this.fibreColour.needsUpdate = true;
      this.fibres.geometry.computeBoundingSphere();
    }

    this.landmarks.forEach(function (l) {
      var px = x[3 * l.node], py = x[3 * l.node + 1], pz = x[3 * l.node + 2];
      l.sphere.position.set(px, py, pz);
      var h = l.history;
      // a jump back in time (seek, reset, new run) starts the trail again
      if (h.length && frame.time < h[h.length - 1][0]) h.length = 0;
      if (!h.length || h[h.length - 1][0] !== frame.time) h.push([frame.time, px, py, pz]);
      while (h.length > TRAIL_POINTS || (h.length && h[0][0] < frame.time - TRAIL_SECONDS)) h.shift();
      var tp = l.trailPosition.array;
      for (var k = 0; k < h.length; k++) { tp[3 * k] = h[k][1]; tp[3 * k + 1] = h[k][2]; tp[3 * k + 2] = h[k][3]; }
      l.trailPosition.needsUpdate = true;
      l.trail.geometry.setDrawRange(0, h.length);
    });

    var cn = frame.contactNodes, cf = frame.contactForces, cp = this.contactPosition.array, ap = this.arrowPosition.array;
    var count = Math.min(cn.length, n);
    for (i = 0; i < count; i++) {
      var q = 3 * cn[i];
      cp[3 * i] = ap[6 * i] = x[q]; cp[3 * i + 1] = ap[6 * i + 1] = x[q + 1]; cp[3 * i + 2] = ap[6 * i + 2] = x[q + 2];
      ap[6 * i + 3] = x[q] + cf[3 * i] * ARROW_M_PER_N;
      ap[6 * i + 4] = x[q + 1] + cf[3 * i + 1] * ARROW_M_PER_N;
      ap[6 * i + 5] = x[q + 2] + cf[3 * i + 2] * ARROW_M_PER_N;
    }
    this.contactPosition.needsUpdate = true;
    this.arrowPosition.needsUpdate = true;
    this.contactPoints.geometry.setDrawRange(0, count);
    this.arrows.geometry.setDrawRange(0, 2 * count);
  };

  RunMesh.prototype.dispose = function () {
    this.group.traverse(function (o) {
      if (o.geometry) o.geometry.dispose();
      if (o.material) o.material.dispose();
    });
  };

  function makeScene() {
    var s = new THREE.Scene();
    s.add(new THREE.HemisphereLight(0xffffff, 0x555566, 0.55));
    var d = new THREE.DirectionalLight(0xffffff, 0.6);
    s.add(d); s.add(d.target);
    s.userData.light = d;
    return s;
  }

  // container: the element holding the canvas (for its size); canvas: #view3d; legend: #legend
  function View3D(container, canvas, legend) {
    this.container = container;
    this.canvas = canvas;
    this.legend = legend;
    this.renderer = new THREE.WebGLRenderer({ canvas: canvas, antialias: true, preserveDrawingBuffer: true });
    this.renderer.setPixelRatio(window.devicePixelRatio || 1);
    this.renderer.setClearColor(0xf4f4f0);
    this.camera = new THREE.PerspectiveCamera(FOV, 1, 0.001, 2);
    this.controls = new THREE.OrbitControls(this.camera, canvas);
    this.controls.addEventListener("change", this.render.bind(this));
    this.panes = [];                    // {scene, runs: [RunMesh], label}
    this.runs = [];
    this.side = false;
    this.cameraName = "left";
    this.labels = [];
  }

  // models: one or two prepared models; side: two panes rather than one overlay
  View3D.prototype.setModels = function (models, side, names) {
    this.runs.forEach(function (r) { r.dispose(); });
    this.panes.forEach(function (p) { p.scene.traverse(function (o) { if (o.geometry) o.geometry.dispose(); }); });
    this.side = side && models.length > 1;
    this.panes = [];
    var paneCount = this.side ? 2 : 1;
    for (var k = 0; k < paneCount; k++) this.panes.push({ scene: makeScene(), runs: [] });
    this.runs = models.map(function (m, r) {
      var mesh = new RunMesh(m, r > 0 && !this.side);
      var pane = this.panes[this.side ? r : 0];
      pane.scene.add(mesh.group);
      pane.runs.push(mesh);
      // each obstacle once per pane: overlaid runs of one scene share theirs
      pane.obstacleNames = pane.obstacleNames || [];
      m.obstacles.forEach(function (o) {
        if (pane.obstacleNames.indexOf(o.name) >= 0) return;
        pane.obstacleNames.push(o.name);
        pane.scene.add(obstacleMesh(o));
      });
      return mesh;
    }, this);

    // frame the tongue and the obstacles
    var pts = [];
    models.forEach(function (m) {
      pts.push(m.box.min, m.box.max);
      m.obstacles.forEach(function (o) { var b = TongueModel.boundingBox(o.vertices); pts.push(b.min, b.max); });
    });
    this.box = TongueModel.boundingBox([].concat.apply([], pts));
    this.target = new THREE.Vector3().fromArray(this.box.center);

    this.labels.forEach(function (l) { l.remove(); });
    this.labels = [];
    if (models.length > 1 && names) {
      var texts = this.side ? names : [names[0] + " (surface colours)", names[1] + " (orange wireframe)"];
      texts.forEach(function (t, i) {
        var d = document.createElement("div");
        d.className = "pane-label" + (this.side ? " pane-" + i : " pane-overlay-" + i);
        d.textContent = t;
        this.container.appendChild(d);
        this.labels.push(d);
      }, this);
    }
    this.resize();
    this.setCamera(this.cameraName);
  };

  View3D.prototype.setCamera = function (name) {
    if (!CAMERAS[name]) name = "left";
    this.cameraName = name;
    if (!this.box) return;
    var dir = new THREE.Vector3().fromArray(CAMERAS[name]).normalize();
    var s = this.box.size, radius = 0.5 * Math.sqrt(s[0] * s[0] + s[1] * s[1] + s[2] * s[2]);
    var vfov = FOV * Math.PI / 180, hfov = 2 * Math.atan(Math.tan(vfov / 2) * this.camera.aspect);
    var dist = radius / Math.sin(Math.min(vfov, hfov) / 2) * 0.95;   // the bounding sphere, just
    this.camera.position.copy(this.target).addScaledVector(dir, dist);
    this.camera.up.set(0, 1, 0);
    this.camera.lookAt(this.target);
    this.controls.target.copy(this.target);
    this.controls.update();             // fires "change", which renders
  };

  // frames[r] drawn for run r (missing: left as it is). Returns nothing; renders.
  View3D.prototype.update = function (frames, field, showFibres) {
    var scale = 1;
    if (field === "displacement") {
      var most = 0;
      this.runs.forEach(function (r, k) {
        var f = frames[k], m = r.model;
        if (!f) return;
        for (var i = 0; i < 3 * m.numNodes; i += 3) {
          var dx = f.positions[i] - m.rest[i], dy = f.positions[i + 1] - m.rest[i + 1], dz = f.positions[i + 2] - m.rest[i + 2];
          most = Math.max(most, dx * dx + dy * dy + dz * dz);
        }
      });
      scale = niceCeil(Math.sqrt(most) * 1000);   // mm, a round number so the legend reads easily
    }
    this.runs.forEach(function (r, k) { if (frames[k]) r.update(frames[k], field, scale, showFibres); });
    this.showLegend(field, scale);
    this.render();
  };

  View3D.prototype.showLegend = function (field, scale) {
    var L = this.legend, bar = '<span class="legend-bar" style="background:' + Colormap.cssGradient() + '"></span>';
    var arrows = this.runs.some(function (r) { return r.model.obstacles.length; })
      ? '<div>contact: red dots, force arrows 1 N = ' + ARROW_M_PER_N * 1000 + ' mm</div>' : "";
    if (field === "displacement") L.innerHTML = "<div>displacement |x − X|</div><div>0 " + bar + " " + scale + " mm</div>" + arrows;
    else if (field === "activation") L.innerHTML = "<div>activation of the most active muscle</div><div>0 " + bar + " 1</div>" + arrows;
    else L.innerHTML = "<div>most active muscle (colours of the bars); grey: none active</div>" + arrows;
  };

  View3D.prototype.resize = function () {
    var w = Math.max(1, this.container.clientWidth), h = Math.max(1, this.container.clientHeight);
    this.renderer.setSize(w, h, false);
    this.width = w; this.height = h;
    this.camera.aspect = (this.side ? w / 2 : w) / h;
    this.camera.updateProjectionMatrix();
    this.render();
  };

  View3D.prototype.render = function () {
    var r = this.renderer, w = this.width || 1, h = this.height || 1, cam = this.camera, target = this.controls.target;
    r.setScissorTest(true);
    var paneW = this.side ? Math.floor(w / 2) : w;
    if (!this.panes.length) { r.setScissor(0, 0, w, h); r.clear(); }
    this.panes.forEach(function (p, i) {
      var light = p.scene.userData.light;
      light.position.copy(cam.position);          // light from the eye: no side goes dark
      light.target.position.copy(target);
      var pw = i === this.panes.length - 1 ? w - i * paneW : paneW;   // the last pane takes an odd pixel
      r.setViewport(i * paneW, 0, pw, h);
      r.setScissor(i * paneW, 0, pw, h);
      r.render(p.scene, cam);
    }, this);
    r.setScissorTest(false);
  };

  return { View3D: View3D };
})();
