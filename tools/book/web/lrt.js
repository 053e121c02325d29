// lrt.js: the web edition's behaviour: MathJax's configuration, the side bar
// that folds on a narrow screen, and the search box over the index that
// tools/book/html_site.py writes (search-index.js: window.LRT_SEARCH, a list of
// {k: kind, t: text, n: number, u: url}).
'use strict';

// MathJax (loaded after this file, on pages with mathematics) typesets only
// what pandoc marked as mathematics, reports TeX it cannot read on the
// console, and marks the page data-math="done" when it has finished, which
// the browser tests wait for. Pages without mathematics are marked "none".
window.MathJax = {
  tex2jax: {
    inlineMath: [['\\(', '\\)']],
    displayMath: [['\\[', '\\]']],
    processEscapes: false,
    ignoreClass: '.*',
    processClass: 'math'
  },
  TeX: {noErrors: {disabled: true}, noUndefined: {disabled: true}},
  messageStyle: 'none',
  showMathMenu: false,
  CommonHTML: {linebreaks: {automatic: false}},
  AuthorInit: function () {
    var hub = window.MathJax.Hub;
    hub.Register.MessageHook('TeX Jax - parse error', function (message) {
      console.error('TeX error: ' + message[1] + ' in ' + message[2]);
    });
    hub.Register.MessageHook('Math Processing Error', function (message) {
      console.error('MathJax: ' + message[2]);
    });
    hub.Register.StartupHook('End', function () {
      document.documentElement.setAttribute('data-math', 'done');
    });
  }
};

document.addEventListener('DOMContentLoaded', function () {
  if (!document.querySelector('script[src*="MathJax.js"]')) {
    document.documentElement.setAttribute('data-math', 'none');
  }

  // The side bar: always shown on a wide screen, folded behind a button on a
  // narrow one.
  var toggle = document.querySelector('.navtoggle');
  var sidebar = document.getElementById('sidebar');
  function setOpen(open) {
    document.body.classList.toggle('nav-open', open);
    toggle.setAttribute('aria-expanded', open ? 'true' : 'false');
  }
  toggle.addEventListener('click', function () {
    setOpen(!document.body.classList.contains('nav-open'));
  });
  sidebar.addEventListener('click', function (event) {
    if (event.target.closest('a')) setOpen(false);
  });
  var current = sidebar.querySelector('[aria-current="page"]');
  if (current && current.scrollIntoView) current.scrollIntoView({block: 'center'});

  // The search: every word of the query must begin a word of the entry (or,
  // from three letters on, appear inside one); whole words count most,
  // then sections before fragments before identifiers, then shorter names.
  var input = document.getElementById('search');
  var list = document.getElementById('search-results');
  var KINDS = {s: 'Section', f: 'Fragment', i: 'Identifier'};
  var RANK = {s: 2, f: 1, i: 0};
  var LIMIT = 40;

  function words(text) {
    return text.toLowerCase().split(/[^a-z0-9_]+/).filter(Boolean);
  }

  function score(entry, query) {
    if (!entry.w) entry.w = words(entry.t);
    var total = 0;
    for (var i = 0; i < query.length; i++) {
      var q = query[i], best = 0;
      for (var j = 0; j < entry.w.length && best < 3; j++) {
        var w = entry.w[j];
        if (w === q) best = 3;
        else if (w.indexOf(q) === 0) best = Math.max(best, 2);
        else if (q.length >= 3 && w.indexOf(q) > 0) best = Math.max(best, 1);
      }
      if (!best) return 0;
      total += best;
    }
    return total * 10 + RANK[entry.k];
  }

  function search(text) {
    var query = words(text);
    if (!query.length || !window.LRT_SEARCH) return [];
    var found = [];
    window.LRT_SEARCH.forEach(function (entry) {
      var s = score(entry, query);
      if (s) found.push({entry: entry, score: s});
    });
    found.sort(function (a, b) {
      return b.score - a.score || a.entry.t.length - b.entry.t.length ||
             (a.entry.t < b.entry.t ? -1 : 1);
    });
    return found.slice(0, LIMIT).map(function (f) { return f.entry; });
  }

  function show(results) {
    list.textContent = '';
    results.forEach(function (entry) {
      var item = document.createElement('li');
      var link = document.createElement('a');
      link.href = entry.u;
      link.className = 'result-' + entry.k;
      var kind = document.createElement('span');
      kind.className = 'kind';
      kind.textContent = KINDS[entry.k];
      var name = document.createElement(entry.k === 'i' ? 'code' : 'span');
      name.className = 'name';
      name.textContent = entry.k === 'f' ? '⟨' + entry.t + '⟩' : entry.t;
      var number = document.createElement('span');
      number.className = 'number';
      number.textContent = entry.n;
      link.append(kind, ' ', name, ' ', number);
      item.appendChild(link);
      list.appendChild(item);
    });
    if (input.value.trim() && !results.length) {
      var none = document.createElement('li');
      none.className = 'none';
      none.textContent = 'Nothing found.';
      list.appendChild(none);
    }
    list.hidden = !input.value.trim();
    sidebar.classList.toggle('searching', !list.hidden);
  }

  input.addEventListener('input', function () { show(search(input.value)); });
  input.addEventListener('keydown', function (event) {
    if (event.key === 'Enter') {
      var first = list.querySelector('a');
      if (first) window.location.href = first.href;
    } else if (event.key === 'Escape') {
      input.value = '';
      show([]);
    }
  });
});
