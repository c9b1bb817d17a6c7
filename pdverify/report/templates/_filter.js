/* The page's filters: paper, model, variant and scene. A table row or figure carries data-paper, data-model,
   data-variant, data-scene ('|'-separated where it belongs to several); a figure's lines carry their model and
   variant, so a filter hides lines inside a figure and the figure when none is left. A block (class fgroup)
   hides when everything filterable in it is hidden. */
(function () {
  "use strict";
  var form = document.getElementById("filters");
  if (!form) return;
  var KEYS = ["paper", "model", "variant", "scene"];
  var NONE = "-";  // the variant of a model without variants

  function values(el, key) {
    var v = el.getAttribute("data-" + key);
    return v === null ? null : v.split("|").map(function (x) { return x === "" ? NONE : x; });
  }
  function matches(el, f, keys) {
    return keys.every(function (k) {
      if (!f[k]) return true;
      var v = values(el, k);
      return v !== null && v.indexOf(f[k]) >= 0;
    });
  }
  function lineMatches(s, f) {
    return (!f.model || s.m === f.model) && (!f.variant || (s.v || NONE) === f.variant);
  }

  function apply() {
    var f = {};
    KEYS.forEach(function (k) { f[k] = form.elements[k].value; });
    var rows = 0, rowsShown = 0, figs = 0, figsShown = 0;
    document.querySelectorAll(".f").forEach(function (el) {
      var show = matches(el, f, KEYS);
      el.hidden = !show;
      rows += 1;
      rowsShown += show ? 1 : 0;
    });
    var registry = window.pdvFigures || {list: [], refresh: function () {}};
    registry.list.forEach(function (fig) {
      var spec = fig._spec, changed = false, any = false, data = false;
      spec.s.forEach(function (s) {
        var hide = !s.g && !lineMatches(s, f);
        if (!s.g) { data = true; any = any || !hide; }
        if (Boolean(s._hidden) !== hide) { s._hidden = hide; changed = true; }
      });
      var show = matches(fig, f, ["paper", "scene"]) && (any || !data);
      fig.hidden = !show;
      figs += 1;
      figsShown += show ? 1 : 0;
      if (changed) fig._stale = true;  // drawn again when it shows
      if (show && fig._stale) { fig._stale = false; registry.refresh(fig); }
    });
    document.querySelectorAll(".fgroup").forEach(function (g) {
      var inside = g.querySelectorAll(".f, figure.pfig");
      if (!inside.length) return;
      g.hidden = !Array.prototype.some.call(inside, function (el) { return !el.hidden; });
    });
    var active = KEYS.some(function (k) { return f[k]; });
    document.getElementById("fcount").textContent = active
      ? "showing " + figsShown + " of " + figs + " figures and " + rowsShown + " of " + rows + " table rows"
      : "";
    document.body.classList.toggle("filtered", active);
  }
  form.addEventListener("change", apply);
  form.addEventListener("reset", function () { setTimeout(apply, 0); });
  window.pdvFilter = apply;
})();
