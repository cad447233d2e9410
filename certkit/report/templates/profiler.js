// Prediction profiler of the study report: evaluates the exported surrogates in the page (no network).
// Its arithmetic mirrors, point by point, the Python evaluator of the exported surrogates (evaluate_export).
(function () {
  "use strict";
  var holder = document.getElementById("profiler-data");
  var root = document.getElementById("profiler");
  if (!holder || !root) { return; }
  var data = JSON.parse(holder.textContent);
  var vars = data.variables, resp = data.responses;
  var x = vars.map(function (v) { return v.value; });
  var W = 160, H = 92, PAD = 4, NPTS = 61;

  function evaluate(doc, point) {
    var u = [], i, j, k, y;
    for (i = 0; i < point.length; i++) { u.push((point[i] - doc.lo[i]) * (2.0 / (doc.hi[i] - doc.lo[i])) - 1.0); }
    if (doc.kind === "polynomial") {
      y = doc.intercept;
      for (k = 0; k < doc.coef.length; k++) {
        var prod = doc.coef[k], term = doc.terms[k];
        for (j = 0; j < term.length; j++) { prod *= Math.pow(u[term[j][0]], term[j][1]); }
        y += prod;
      }
    } else if (doc.kind === "mlp") {
      var h = u, layers = doc.weights.length;
      for (k = 0; k < layers; k++) {
        var w = doc.weights[k], b = doc.biases[k], z = [];
        for (j = 0; j < b.length; j++) {
          var s = b[j];
          for (i = 0; i < h.length; i++) { s += w[i][j] * h[i]; }
          z.push(k < layers - 1 ? Math.tanh(s) : s);
        }
        h = z;
      }
      y = h[0] * doc.scale + doc.mean;
    } else if (doc.kind === "gp") {
      var acc = 0.0, ls = doc.length_scale;
      for (j = 0; j < doc.x.length; j++) {
        var d2 = 0.0, xj = doc.x[j];
        for (i = 0; i < u.length; i++) { var t = (u[i] - xj[i]) / ls[ls.length > 1 ? i : 0]; d2 += t * t; }
        acc += doc.alpha[j] * doc.constant * Math.exp(-0.5 * d2);
      }
      y = doc.mean + doc.std * acc;
    } else {
      throw new Error("unknown model kind " + doc.kind);
    }
    return doc.log ? Math.exp(y) : y;
  }

  function fmt(v) {
    if (!isFinite(v)) { return "—"; }
    var a = Math.abs(v);
    return (a !== 0 && (a < 1e-3 || a >= 1e5)) ? v.toExponential(3) : v.toPrecision(4);
  }

  // SVG is written as markup (the HTML parser puts it in the SVG namespace): no namespace URL in the page
  function tag(name, attrs, text) {
    var s = "<" + name;
    for (var k in attrs) { if (Object.prototype.hasOwnProperty.call(attrs, k)) { s += " " + k + "=\"" + attrs[k] + "\""; } }
    return s + ">" + (text || "") + "</" + name + ">";
  }

  // sliders
  var sliders = document.createElement("div");
  sliders.className = "sliders";
  root.appendChild(sliders);
  vars.forEach(function (v, i) {
    var row = document.createElement("label");
    row.className = "slider";
    var name = document.createElement("span");
    name.textContent = v.label;
    name.title = v.path;
    var input = document.createElement("input");
    input.type = "range"; input.min = v.from; input.max = v.to; input.step = "any"; input.value = v.value;
    input.id = "pslider-" + i;
    var out = document.createElement("output");
    out.id = "pvalue-" + i;
    input.addEventListener("input", function () { x[i] = parseFloat(input.value); update(); });
    row.appendChild(name); row.appendChild(input); row.appendChild(out);
    sliders.appendChild(row);
  });

  // grid: one row per response, one cell per variable
  var wrap = document.createElement("div");
  wrap.className = "scroll";
  var table = document.createElement("table");
  table.className = "profiler-grid";
  wrap.appendChild(table);
  root.appendChild(wrap);
  var head = table.insertRow();
  var th = document.createElement("th"); th.textContent = "response at the current point"; head.appendChild(th);
  vars.forEach(function (v) { var c = document.createElement("th"); c.textContent = v.label; c.title = v.path; head.appendChild(c); });
  var cells = resp.map(function (r, j) {
    var tr = table.insertRow();
    var name = tr.insertCell();
    name.className = "pred" + (r.flagged ? " flagged" : "");
    name.id = "presp-" + j;
    name.setAttribute("data-response", r.name);
    name.title = r.name;
    return vars.map(function () { return tr.insertCell(); });
  });

  function curve(r, i) {
    var v = vars[i], pts = [], k, p = x.slice();
    for (k = 0; k < NPTS; k++) {
      p[i] = v.from + (v.to - v.from) * k / (NPTS - 1);
      pts.push([p[i], evaluate(r.model, p)]);
    }
    return pts;
  }

  // one y scale per response row (all its curves and limits), so that a flat dependence looks flat
  function drawRow(r, j, y0) {
    var curves = vars.map(function (v, i) { return curve(r, i); });
    var ys = [y0];
    curves.forEach(function (pts) { pts.forEach(function (q) { if (isFinite(q[1])) { ys.push(q[1]); } }); });
    var lims = [r.min, r.max].filter(function (t) { return t !== null && t !== undefined; });
    var ymin = Math.min.apply(null, ys.concat(lims)), ymax = Math.max.apply(null, ys.concat(lims));
    var pad = 0.05 * (ymax - ymin) || Math.abs(ymin) * 1e-3 || 1;
    ymin -= pad; ymax += pad;
    cells[j].forEach(function (td, i) { draw(td, r, i, y0, curves[i], lims, ymin, ymax); });
  }

  function draw(td, r, i, y0, pts, lims, ymin, ymax) {
    var v = vars[i];
    var sx = function (t) { return (PAD + (W - 2 * PAD) * (t - v.from) / (v.to - v.from)).toFixed(2); };
    var sy = function (t) { return (H - PAD - (H - 2 * PAD) * (t - ymin) / (ymax - ymin)).toFixed(2); };
    var hstep = 1e-4 * (v.upper - v.lower), a = x.slice(), b = x.slice();
    a[i] -= hstep; b[i] += hstep;
    var slope = (evaluate(r.model, b) - evaluate(r.model, a)) / (2 * hstep);
    var dx = 0.15 * (v.to - v.from);
    var body = tag("rect", {x: 0, y: 0, width: sx(v.lower), height: H, "class": "outside"}) +
      tag("rect", {x: sx(v.upper), y: 0, width: (W - sx(v.upper)).toFixed(2), height: H, "class": "outside"});
    lims.forEach(function (t) { body += tag("line", {x1: 0, x2: W, y1: sy(t), y2: sy(t), "class": "limit"}); });
    body += tag("polyline", {points: pts.map(function (q) { return sx(q[0]) + "," + sy(q[1]); }).join(" "), "class": "curve"});
    body += tag("line", {x1: sx(x[i] - dx), y1: sy(y0 - slope * dx), x2: sx(x[i] + dx), y2: sy(y0 + slope * dx), "class": "slope"});
    body += tag("line", {x1: sx(x[i]), x2: sx(x[i]), y1: 0, y2: H, "class": "current"});
    body += tag("text", {x: W - PAD, y: 11, "text-anchor": "end", "class": "slope-text"}, "slope " + fmt(slope));
    td.innerHTML = tag("svg", {viewBox: "0 0 " + W + " " + H, width: W, height: H, "class": "prof",
      "data-slope": String(slope)}, body);
  }

  // the classifier of possible designs (a logistic regression on a polynomial of the variables), as
  // certkit.study.analysis.validity.validity_log_odds evaluates it
  function logOdds(doc, point) {
    var s = doc.intercept, i, k;
    for (k = 0; k < doc.coef.length; k++) {
      var f = 1.0, term = doc.terms[k];
      for (i = 0; i < term.length; i++) {
        var u = (point[term[i][0]] - doc.lo[term[i][0]]) * (2.0 / (doc.hi[term[i][0]] - doc.lo[term[i][0]])) - 1.0;
        f *= Math.pow(u, term[i][1]);
      }
      s += doc.coef[k] * (f - doc.mean[k]) / doc.scale[k];
    }
    return s;
  }
  var possible = document.createElement("p");
  possible.id = "pvalid";
  root.insertBefore(possible, root.firstChild);

  function update() {
    if (data.validity) {
      var z = logOdds(data.validity, x), p = 1.0 / (1.0 + Math.exp(-z));
      possible.setAttribute("data-impossible", z > 0 ? "1" : "0");
      possible.textContent = (z > 0 ? "Impossible planform at this point" : "Possible aircraft at this point") +
        " (classifier of the study's infeasible cases: P(impossible) = " + p.toFixed(3) + ")" +
        (z > 0 ? ": the predictions below are not a design." : ".");
    } else {
      possible.setAttribute("data-impossible", "0");
      possible.textContent = "No impossible design among the cases: every point is taken as a possible aircraft.";
    }
    vars.forEach(function (v, i) {
      var out = document.getElementById("pvalue-" + i);
      out.textContent = fmt(x[i] / (v.factor || 1)) + (v.unit ? " " + v.unit : "") + ((x[i] < v.lower || x[i] > v.upper) ? " (outside the sampled region)" : "");
    });
    resp.forEach(function (r, j) {
      var y0 = evaluate(r.model, x);
      var cell = document.getElementById("presp-" + j);
      cell.setAttribute("data-value", String(y0));
      var lim = [];
      var k = r.factor || 1, unit = r.unit ? " " + r.unit : "";
      if (r.min !== null && r.min !== undefined) { lim.push("≥ " + fmt(r.min / k) + unit); }
      if (r.max !== null && r.max !== undefined) { lim.push("≤ " + fmt(r.max / k) + unit); }
      cell.textContent = (r.title || r.name) + " = " + fmt(y0 / k) + unit + (lim.length ? " (" + lim.join(", ") + ")" : "") +
        (r.flagged ? " — surrogate flagged (R² below threshold)" : "");
      drawRow(r, j, y0);
    });
  }
  update();
  root.setAttribute("data-ready", "1");
}());
