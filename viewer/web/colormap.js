// Colours of the viewer: the 0..1 colour map (fields, fibres) and one colour per muscle group.
// Colours are [r, g, b] in 0..1 so that they go straight into three.js buffers.
var Colormap = (function () {
  "use strict";

  // Viridis, sampled at 9 stops: perceptually even and readable in grey.
  var STOPS = [
    [0.267, 0.005, 0.329], [0.278, 0.175, 0.483], [0.231, 0.322, 0.545],
    [0.173, 0.449, 0.558], [0.128, 0.567, 0.551], [0.153, 0.683, 0.499],
    [0.360, 0.785, 0.387], [0.667, 0.862, 0.196], [0.993, 0.906, 0.144]
  ];

  var GREY = [0.72, 0.70, 0.68];          // surface where no muscle is active
  var SECOND_RUN = [0.95, 0.45, 0.10];    // the compared (second) run, overlaid

  // Left and right halves of a muscle share a colour: the group is what a reader looks for.
  var GROUP_COLOURS = {
    GGp: [0.85, 0.15, 0.15], GGm: [0.95, 0.50, 0.10], GGa: [0.90, 0.80, 0.10],
    HG: [0.20, 0.65, 0.25], SG: [0.15, 0.45, 0.90], IL: [0.55, 0.25, 0.80],
    T: [0.95, 0.35, 0.70], V: [0.10, 0.75, 0.75], MH: [0.55, 0.35, 0.15],
    SL: [0.40, 0.40, 0.95]
  };
  var SPARE = [[0.60, 0.60, 0.20], [0.20, 0.50, 0.50], [0.70, 0.20, 0.45], [0.35, 0.55, 0.85]];

  function clamp01(v) { return v < 0 ? 0 : (v > 1 ? 1 : v); }

  // v in 0..1 (clamped; NaN counts as 0) -> [r, g, b]
  function map(v, out) {
    out = out || [0, 0, 0];
    v = clamp01(v || 0) * (STOPS.length - 1);
    var i = Math.min(Math.floor(v), STOPS.length - 2), f = v - i;
    for (var k = 0; k < 3; k++) out[k] = STOPS[i][k] * (1 - f) + STOPS[i + 1][k] * f;
    return out;
  }

  function groupOf(name) { return String(name).replace(/_(left|right)$/, ""); }

  // Muscles of an imported tongue may have names of their own: they get spare colours in order.
  function muscleColours(names) {
    var spare = 0;
    return names.map(function (n) {
      return GROUP_COLOURS[groupOf(n)] || SPARE[spare++ % SPARE.length];
    });
  }

  function css(rgb, alpha) {
    var c = rgb.map(function (v) { return Math.round(clamp01(v) * 255); });
    return alpha === undefined ? "rgb(" + c.join(",") + ")" : "rgba(" + c.join(",") + "," + alpha + ")";
  }

  // A CSS linear-gradient of the map, for the legend.
  function cssGradient() {
    return "linear-gradient(to right," + STOPS.map(function (s) { return css(s); }).join(",") + ")";
  }

  return { map: map, muscleColours: muscleColours, css: css, cssGradient: cssGradient,
           GREY: GREY, SECOND_RUN: SECOND_RUN };
})();
