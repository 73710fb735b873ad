// The Model and Frame JSON checked and turned into what the views draw from. Bad data throws an
// Error naming the field, which the page shows in the status line; nothing else parses JSON.
var TongueModel = (function () {
  "use strict";

  function fail(what) { throw new Error(what); }

  function numbers(a, what, length) {
    if (!Array.isArray(a)) fail(what + " is not an array");
    if (length !== undefined && a.length !== length) fail(what + " has " + a.length + " values, expected " + length);
    for (var i = 0; i < a.length; i++) if (typeof a[i] !== "number" || !isFinite(a[i])) fail(what + "[" + i + "] is not a finite number");
    return a;
  }

  function indices(a, what, limit) {
    numbers(a, what);
    for (var i = 0; i < a.length; i++) {
      if (a[i] < 0 || a[i] >= limit || a[i] % 1 !== 0) fail(what + "[" + i + "] = " + a[i] + " is not an index below " + limit);
    }
    return a;
  }

  function boundingBox(xyz) {
    var min = [Infinity, Infinity, Infinity], max = [-Infinity, -Infinity, -Infinity];
    for (var i = 0; i < xyz.length; i += 3) {
      for (var k = 0; k < 3; k++) {
        if (xyz[i + k] < min[k]) min[k] = xyz[i + k];
        if (xyz[i + k] > max[k]) max[k] = xyz[i + k];
      }
    }
    return { min: min, max: max,
             center: [0, 1, 2].map(function (k) { return (min[k] + max[k]) / 2; }),
             size: [0, 1, 2].map(function (k) { return max[k] - min[k]; }) };
  }

  // Model JSON -> the prepared model (see the return statement for its fields).
  function prepare(json) {
    if (!json || typeof json !== "object") fail("model: not an object");
    var n = json.num_nodes;
    if (typeof n !== "number" || n <= 0 || n % 1 !== 0) fail("model: num_nodes is not a positive integer");
    var rest = new Float64Array(numbers(json.rest_positions, "model.rest_positions", 3 * n));

    var quads = indices(json.surface || [], "model.surface", n);
    if (quads.length % 4 !== 0 || quads.length === 0) fail("model.surface: " + quads.length + " indices is not a non-empty list of quads");
    // two triangles per quad (cyclic a b c d -> a b c, a c d)
    var tris = new Uint32Array(quads.length / 4 * 6);
    for (var q = 0, t = 0; q < quads.length; q += 4) {
      tris[t++] = quads[q]; tris[t++] = quads[q + 1]; tris[t++] = quads[q + 2];
      tris[t++] = quads[q]; tris[t++] = quads[q + 2]; tris[t++] = quads[q + 3];
    }

    // the quads' unique edges, for the wireframe of an overlaid run (no triangle diagonals)
    var seen = {}, edges = [];
    for (q = 0; q < quads.length; q += 4) {
      for (var e = 0; e < 4; e++) {
        var a = quads[q + e], b = quads[q + (e + 1) % 4], key = a < b ? a * n + b : b * n + a;
        if (!seen[key]) { seen[key] = true; edges.push(a, b); }
      }
    }

    var muscles = (json.muscles || []).map(function (m, i) {
      if (!m || typeof m.name !== "string") fail("model.muscles[" + i + "] has no name");
      return { name: m.name, maxForce: Number(m.max_force) };
    });
    var colours = Colormap.muscleColours(muscles.map(function (m) { return m.name; }));
    muscles.forEach(function (m, i) { m.colour = colours[i]; });

    var fj = json.fibres || { muscle: [], offsets: [0], nodes: [], origins: [] };
    var fMuscle = indices(fj.muscle || [], "model.fibres.muscle", Math.max(muscles.length, 1));
    var F = fMuscle.length;
    // no fibres: [0] by the contract; [] (what a run file without muscles gives) means the same
    var offsets = F === 0 && (!fj.offsets || !fj.offsets.length) ? [0] : numbers(fj.offsets, "model.fibres.offsets", F + 1);
    var fNodes = indices(fj.nodes || [], "model.fibres.nodes", n);
    if (offsets[0] !== 0 || offsets[F] !== fNodes.length) fail("model.fibres.offsets do not span model.fibres.nodes");
    for (var f = 0; f < F; f++) if (offsets[f + 1] < offsets[f]) fail("model.fibres.offsets decrease at " + f);
    var rawOrigins = fj.origins || [];
    if (rawOrigins.length !== 3 * F) fail("model.fibres.origins has " + rawOrigins.length + " values, expected " + 3 * F);
    var origins = new Float64Array(3 * F);
    for (var i = 0; i < 3 * F; i++) origins[i] = rawOrigins[i] === null ? NaN : Number(rawOrigins[i]);

    // the muscles whose fibres pass through each node, for the "muscle" and "activation" fields
    var nodeMuscles = [];
    for (i = 0; i < n; i++) nodeMuscles.push([]);
    for (f = 0; f < F; f++) {
      for (var j = offsets[f]; j < offsets[f + 1]; j++) {
        var list = nodeMuscles[fNodes[j]];
        if (list.indexOf(fMuscle[f]) < 0) list.push(fMuscle[f]);
      }
    }

    var landmarks = (json.landmarks || []).map(function (l, i) {
      if (!l || typeof l.name !== "string" || !(l.node >= 0 && l.node < n)) fail("model.landmarks[" + i + "] is not {name, node < " + n + "}");
      return { name: l.name, node: l.node };
    });

    var obstacles = (json.obstacles || []).map(function (o, i) {
      var what = "model.obstacles[" + i + "]";
      var v = numbers(o.vertices, what + ".vertices");
      if (v.length % 3 !== 0) fail(what + ".vertices is not 3 per vertex");
      var tr = indices(o.triangles, what + ".triangles", v.length / 3);
      if (tr.length % 3 !== 0) fail(what + ".triangles is not 3 per triangle");
      return { name: String(o.name), vertices: new Float64Array(v), triangles: new Uint32Array(tr) };
    });

    var box = boundingBox(rest);
    return {
      version: json.version,
      numNodes: n,
      rest: rest,                      // m, 3N
      surfaceTriangles: tris,          // node indices, 3 per triangle
      surfaceEdges: new Uint32Array(edges),   // node indices, 2 per edge of the boundary quads
      muscles: muscles,                // {name, maxForce, colour}
      fibres: { muscle: fMuscle, offsets: offsets, nodes: fNodes, origins: origins },  // origins NaN: none
      nodeMuscles: nodeMuscles,
      landmarks: landmarks,
      obstacles: obstacles,
      dt: Number(json.dt),
      box: box,                        // of the rest positions
      midZ: box.center[2],             // the midsagittal plane
      scene: json.scene || ""
    };
  }

  // Frame JSON -> {step, time, positions (Float64Array 3N, m), activations, ...}. A frame with
  // node indices updates those nodes of the previous positions (or of the rest positions).
  function readFrame(model, json, previous) {
    if (!json || json.type !== "frame") fail("frame: not a frame message");
    var n = model.numNodes, pos;
    if (json.nodes === null || json.nodes === undefined) {
      pos = new Float64Array(numbers(json.positions, "frame.positions", 3 * n));
    } else {
      var nodes = indices(json.nodes, "frame.nodes", n);
      var p = numbers(json.positions, "frame.positions", 3 * nodes.length);
      pos = new Float64Array(previous || model.rest);
      for (var i = 0; i < nodes.length; i++) {
        pos[3 * nodes[i]] = p[3 * i]; pos[3 * nodes[i] + 1] = p[3 * i + 1]; pos[3 * nodes[i] + 2] = p[3 * i + 2];
      }
    }
    var acts = numbers(json.activations || [], "frame.activations");
    if (acts.length !== model.muscles.length) fail("frame.activations has " + acts.length + " levels for " + model.muscles.length + " muscles");

    var c = json.contacts || {};
    var cNodes = indices(c.nodes || [], "frame.contacts.nodes", n);
    var cForces = numbers(c.forces || [], "frame.contacts.forces", 3 * cNodes.length);

    return {
      run: json.run, index: json.index, step: json.step, time: json.time,
      positions: pos, activations: acts,
      iterations: json.iterations, residual: json.residual, cuts: json.cuts,
      converged: json.converged !== false, status: json.status === undefined ? "" : String(json.status),
      realTimeFactor: typeof json.real_time_factor === "number" ? json.real_time_factor : null,
      contactNodes: cNodes, contactForces: cForces,
      maxPenetration: typeof json.max_penetration === "number" ? json.max_penetration : 0,
      reducedCorrection: typeof json.reduced_correction === "number" ? json.reduced_correction : 0,
      dropped: json.dropped || 0
    };
  }

  return { prepare: prepare, readFrame: readFrame, boundingBox: boundingBox };
})();
