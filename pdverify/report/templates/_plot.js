/* pdverify report figures. Each <figure class="pfig"> holds its title (div.ftitle) and its data as JSON: {x/y: {l: label,
   u: unit, log}, s: series [{n: name, x: positions or {a, d, n} (a uniform grid), y, c: colour, k: style,
   m/v: model/variant (the filters), g: a guide line, pl: a label per point}], a: notes, eq: equal scales}.
   Drawn here as SVG when near the screen; hovering shows the nearest point's values; a legend entry toggles its
   line. */
(function () {
  "use strict";
  var NS = "http://www.w3.org/2000/svg";
  var COLOURS = ["#1f77b4", "#ff7f0e", "#2ca02c", "#d62728", "#9467bd", "#8c564b", "#e377c2", "#7f7f7f",
                 "#bcbd22", "#17becf"];
  var DASHES = ["", "7 3", "2 2", "9 3 2 3"];
  var SUPERSCRIPT = {"0": "\u2070", "1": "\u00b9", "2": "\u00b2", "3": "\u00b3", "4": "\u2074", "5": "\u2075",
                     "6": "\u2076", "7": "\u2077", "8": "\u2078", "9": "\u2079", "-": "\u207b"};

  function node(tag, attrs, parent, text) {
    var e = document.createElementNS(NS, tag);
    for (var k in attrs) e.setAttribute(k, attrs[k]);
    if (text !== undefined) e.textContent = text;
    if (parent) parent.appendChild(e);
    return e;
  }
  function colour(c) { return c < 0 ? "#555" : COLOURS[c % COLOURS.length]; }
  function dash(s) {
    if (s.k === "dot") return "2 3";
    if (s.k === "dash" || s.c < 0) return "6 3";
    return DASHES[Math.floor(s.c / COLOURS.length) % DASHES.length];
  }

  function positions(s) {
    var x = s.x;
    if (Array.isArray(x)) return x;
    var out = new Array(x.n);
    for (var i = 0; i < x.n; i++) out[i] = x.a + i * x.d;
    return out;
  }

  /* a number as the read-out shows it: 4 significant digits, exponents without padding */
  function num(v) {
    if (v === null || !isFinite(v)) return "\u2013";
    if (v === 0) return "0";
    var a = Math.abs(v);
    var t = (a >= 1e-3 && a < 1e5) ? String(parseFloat(v.toPrecision(4))) : v.toExponential(2);
    return t.replace(/e\+?(-?)0*(\d)/, "e$1$2");
  }
  function power(k) {
    return "10" + String(k).split("").map(function (ch) { return SUPERSCRIPT[ch]; }).join("");
  }
  /* a tick m·10^k of a log axis: plain between 0.001 and 10000, else a power of ten */
  function logLabel(m, k) {
    if (k >= -3 && k <= 4) return String(parseFloat((m * Math.pow(10, k)).toPrecision(1)));
    return (m === 1 ? "" : m + "\u00b7") + power(k);
  }
  /* a tick of a linear axis: its decimals, or the shortest exponent form for large and small values */
  function linearLabel(v, decimals, exponent) {
    if (!exponent) return v.toFixed(decimals);
    return v === 0 ? "0" : parseFloat(v.toPrecision(6)).toExponential().replace(/e\+?/, "e");
  }

  function range(values, log) {
    var lo = Infinity, hi = -Infinity;
    values.forEach(function (v) {
      if (v === null || !isFinite(v) || (log && v <= 0)) return;
      if (v < lo) lo = v;
      if (v > hi) hi = v;
    });
    if (lo > hi) return log ? [0.1, 10] : [0, 1];
    if (log) {
      if (hi / lo < 1.5) { lo /= 2; hi *= 2; }
      var pad = Math.pow(hi / lo, 0.04);
      return [lo / pad, hi * pad];
    }
    if (lo === hi) { var d = lo === 0 ? 1 : Math.abs(lo) * 0.1; return [lo - d, hi + d]; }
    var p = 0.04 * (hi - lo);
    return [lo - p, hi + p];
  }

  function logTicks(lo, hi) {
    var a = Math.ceil(Math.log10(lo) - 1e-9), b = Math.floor(Math.log10(hi) + 1e-9), ticks = [];
    var step = Math.max(1, Math.ceil((b - a + 1) / 7));
    var plain = b - a < 6;  // a few decades: 0.01 rather than 10⁻² where that is short
    for (var k = a; k <= b; k += step) ticks.push({v: Math.pow(10, k), s: plain ? logLabel(1, k) : power(k)});
    var span = Math.log10(hi / lo);  // under two decades: multiples between the powers of ten
    var between = span < 1 ? [2, 3, 5, 7] : span < 2.2 ? [2, 5] : [];
    for (var j = a - 1; j <= b; j++) between.forEach(function (m) {
      var v = m * Math.pow(10, j);
      if (v > lo && v < hi) ticks.push({v: v, s: logLabel(m, j)});
    });
    return ticks;
  }
  function linearTicks(lo, hi) {
    var raw = (hi - lo) / 5, mag = Math.pow(10, Math.floor(Math.log10(raw))), r = raw / mag;
    var step = mag * (r < 1.5 ? 1 : r < 3 ? 2 : r < 7 ? 5 : 10), ticks = [];
    var decimals = Math.max(0, -Math.floor(Math.log10(step) + 1e-9));
    var big = Math.max(Math.abs(lo), Math.abs(hi));
    for (var v = Math.ceil(lo / step) * step; v <= hi + step * 1e-9; v += step) {
      var w = Math.abs(v) < step * 1e-9 ? 0 : v;
      ticks.push({v: w, s: linearLabel(w, decimals, big >= 1e5 || step < 1e-4)});
    }
    return ticks;
  }

  function Scale(lo, hi, a, b, log) {
    var f = log ? Math.log10 : function (v) { return v; };
    var flo = f(lo), fhi = f(hi);
    this.lo = lo; this.hi = hi; this.log = log;
    this.map = function (v) { return a + (f(v) - flo) / (fhi - flo) * (b - a); };
  }

  function drawable(v, log) { return v !== null && isFinite(v) && (!log || v > 0); }

  function draw(fig) {
    var spec = fig._spec, plot = fig.querySelector(".plot");
    var small = fig.classList.contains("small");
    var W = small ? 300 : 600, H = small ? 210 : 300, L = 62, R = 12, T = 8, B = 40;
    plot.textContent = "";
    var shown = spec.s.filter(function (s) { return !s._hidden && !s._off; });
    var xs = [], ys = [];
    shown.forEach(function (s) {
      s._x = positions(s);
      s._x.forEach(function (v, i) {
        if (drawable(v, spec.x.log) && drawable(s.y[i], spec.y.log)) { xs.push(v); ys.push(s.y[i]); }
      });
    });
    var colours = shown.map(function (s) { return s.c; });
    var notes = (spec.a || []).filter(function (n) { return n.c < 0 || colours.indexOf(n.c) >= 0; });
    notes.forEach(function (n) { xs.push(n.x); ys.push(n.y); });
    var xr = range(xs, spec.x.log), yr = range(ys, spec.y.log);
    if (spec.eq) {  // equal scales: widen the narrower range
      var xw = xr[1] - xr[0], yw = yr[1] - yr[0], px = (W - L - R) / xw, py = (H - T - B) / yw;
      if (px > py) { var cx = (xr[0] + xr[1]) / 2, hx = (W - L - R) / py / 2; xr = [cx - hx, cx + hx]; }
      else { var cy = (yr[0] + yr[1]) / 2, hy = (H - T - B) / px / 2; yr = [cy - hy, cy + hy]; }
    }
    var sx = new Scale(xr[0], xr[1], L, W - R, spec.x.log), sy = new Scale(yr[0], yr[1], H - B, T, spec.y.log);
    var svg = node("svg", {viewBox: "0 0 " + W + " " + H, role: "img", "aria-label": fig._title}, plot);
    var axes = node("g", {"class": "axes"}, svg);
    node("rect", {x: L, y: T, width: W - L - R, height: H - T - B, fill: "none", stroke: "#999"}, axes);
    (spec.x.log ? logTicks(xr[0], xr[1]) : linearTicks(xr[0], xr[1])).forEach(function (t) {
      var X = sx.map(t.v);
      node("line", {x1: X, x2: X, y1: T, y2: H - B, stroke: "#e4e4e4"}, axes);
      node("text", {x: X, y: H - B + 13, "text-anchor": "middle"}, axes, t.s);
    });
    (spec.y.log ? logTicks(yr[0], yr[1]) : linearTicks(yr[0], yr[1])).forEach(function (t) {
      var Y = sy.map(t.v);
      node("line", {x1: L, x2: W - R, y1: Y, y2: Y, stroke: "#e4e4e4"}, axes);
      node("text", {x: L - 4, y: Y + 4, "text-anchor": "end"}, axes, t.s);
    });
    node("text", {x: (L + W - R) / 2, y: H - 6, "text-anchor": "middle", "class": "alabel"}, axes, spec.x.l);
    node("text", {x: 12, y: (T + H - B) / 2, "text-anchor": "middle", "class": "alabel",
                  transform: "rotate(-90 12 " + (T + H - B) / 2 + ")"}, axes, spec.y.l);
    var clipId = "c" + fig._index;
    node("rect", {x: L, y: T, width: W - L - R, height: H - T - B}, node("clipPath", {id: clipId}, svg));
    var lines = node("g", {"clip-path": "url(#" + clipId + ")"}, svg), points = [];
    shown.forEach(function (s) {
      var d = "", pen = false, col = colour(s.c), few = s.y.length <= 12;
      var marks = s.k === "points" || s.k === "line+points" || (few && !s.g);
      s._x.forEach(function (xv, i) {
        var yv = s.y[i];
        if (!drawable(xv, spec.x.log) || !drawable(yv, spec.y.log)) { pen = false; return; }
        var X = sx.map(xv), Y = sy.map(yv);
        d += (pen ? "L" : "M") + X.toFixed(1) + " " + Y.toFixed(1);
        pen = true;
        points.push({X: X, Y: Y, s: s, i: i});
        if (marks) node("circle", {cx: X.toFixed(1), cy: Y.toFixed(1), r: small ? 2.2 : 2.6, fill: col}, lines);
      });
      if (s.k !== "points" && d) {
        node("path", {d: d, fill: "none", stroke: col, "stroke-width": s.g ? 1 : 1.4,
                      "stroke-dasharray": dash(s)}, lines);
      }
    });
    notes.forEach(function (n) {
      if (!drawable(n.x, spec.x.log) || !drawable(n.y, spec.y.log)) return;
      node("text", {x: sx.map(n.x) + 5, y: sy.map(n.y) - 5, fill: colour(n.c), "class": "note"}, svg, n.t);
    });
    legend(fig, spec);
    hover(fig, svg, points, spec, W, H);
  }

  function legend(fig, spec) {
    var old = fig.querySelector(".legend");
    if (old) old.remove();
    var items = spec.s.filter(function (s) { return !s._hidden; });
    if (items.length < 2 && !(items.length === 1 && items[0].g)) {
      if (items.length === 1) fig.querySelector(".plot").setAttribute("title", items[0].n);
      return;
    }
    var ul = document.createElement("ul");
    ul.className = "legend";
    if (items.some(function (s) { return s.n.length > 36; })) ul.classList.add("one");  // long names: one column
    items.forEach(function (s) {
      var li = document.createElement("li");
      li.title = s.n;
      var sw = node("svg", {width: 22, height: 8, "aria-hidden": "true"}, li);
      node("line", {x1: 0, x2: 22, y1: 4, y2: 4, stroke: colour(s.c), "stroke-width": 2, "stroke-dasharray": dash(s)}, sw);
      li.appendChild(document.createTextNode(s.n));
      if (s._off) li.className = "off";
      li.addEventListener("click", function () { s._off = !s._off; draw(fig); });
      ul.appendChild(li);
    });
    fig.querySelector(".plot").after(ul);
  }

  function hover(fig, svg, points, spec, W, H) {
    var tip = document.createElement("div"), dot = null;
    tip.className = "tip";
    tip.hidden = true;
    fig.querySelector(".plot").appendChild(tip);
    svg.addEventListener("mousemove", function (ev) {
      var box = svg.getBoundingClientRect(), mx = (ev.clientX - box.left) * W / box.width,
          my = (ev.clientY - box.top) * H / box.height, best = null, bd = 900;
      points.forEach(function (p) {
        var d = (p.X - mx) * (p.X - mx) + (p.Y - my) * (p.Y - my);
        if (d < bd) { bd = d; best = p; }
      });
      if (dot) { dot.remove(); dot = null; }
      if (!best) { tip.hidden = true; return; }
      dot = node("circle", {cx: best.X, cy: best.Y, r: 4, fill: "none", stroke: "#000"}, svg);
      var s = best.s, unit = function (a) { return a.u ? " " + a.u : ""; };
      tip.textContent = s.n + (s.pl ? " (" + s.pl[best.i] + ")" : "") + "\n" + spec.x.l.split(" (")[0] + " = " +
        num(s._x[best.i]) + unit(spec.x) + "\n" + spec.y.l.split(" (")[0] + " = " + num(s.y[best.i]) + unit(spec.y);
      tip.hidden = false;
      tip.style.left = Math.min(best.X / W * box.width + 10, box.width - 180) + "px";
      tip.style.top = (best.Y / H * box.height + 10) + "px";
    });
    svg.addEventListener("mouseleave", function () { tip.hidden = true; if (dot) { dot.remove(); dot = null; } });
  }

  /* A figure is drawn when it comes near the screen (and before printing): the page opens without drawing the
     figures far below. */
  function ensure(fig) {
    if (!fig._drawn) { fig._drawn = true; draw(fig); }
  }
  var figures = Array.prototype.slice.call(document.querySelectorAll("figure.pfig"));
  figures.forEach(function (fig, i) {
    fig._index = i;
    fig._spec = JSON.parse(fig.querySelector("script").textContent);
    fig._title = (fig.querySelector(".ftitle") || {}).textContent || "";
  });
  if ("IntersectionObserver" in window) {
    var near = new IntersectionObserver(function (entries) {
      entries.forEach(function (e) {
        if (e.isIntersecting) { near.unobserve(e.target); ensure(e.target); }
      });
    }, {rootMargin: "800px 0px"});
    figures.forEach(function (fig) { near.observe(fig); });
  } else {
    figures.forEach(ensure);
  }
  window.addEventListener("beforeprint", function () { figures.forEach(ensure); });
  window.pdvFigures = {
    list: figures,
    refresh: function (fig) { if (fig._drawn) draw(fig); },  // again, after a filter (undrawn: when it shows)
    drawAll: function () { figures.forEach(ensure); }
  };
})();
