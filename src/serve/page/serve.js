// vsil serve's page: keeps the view as `vsil render` flags by key (width_near for --width-near),
// asks /frame for each change (one request in flight; changes made meanwhile go in the next),
// shows the PNG, the command line that reproduces it and the frame time.
'use strict';

const token = new URLSearchParams(location.search).get('token');
const frame = document.getElementById('frame');
const values = {};      // key -> text, or [texts] for a List option; '' clears a flag
let table = null;       // /api/options
let state = null;       // /api/state
let inFlight = false;
let dirty = false;

function api(path) {
  return token ? path + (path.includes('?') ? '&' : '?') + 'token=' + encodeURIComponent(token)
               : path;
}

// Numbers as short text the CLI reads back ("12.5", not "12.500000001").
function num(x, digits = 3) {
  return String(Number(x.toFixed(digits)));
}

function frameUrl() {
  const query = new URLSearchParams();
  for (const [key, value] of Object.entries(values)) {
    if (Array.isArray(value)) {
      if (value.length === 0) query.append(key, '');
      for (const v of value) query.append(key, v);
    } else {
      query.append(key, value);
    }
  }
  return api('frame?' + query.toString());
}

function requestFrame() {
  if (inFlight) { dirty = true; return; }
  inFlight = true;
  dirty = false;
  frame.dataset.busy = '1';  // for tests: '0' once the latest view is shown
  const sent = performance.now();
  fetch(frameUrl()).then(async (response) => {
    if (response.ok) {
      const blob = await response.blob();
      const old = frame.src;
      frame.src = URL.createObjectURL(blob);
      if (old.startsWith('blob:')) URL.revokeObjectURL(old);
      document.getElementById('save').href = frame.src;
      const command = response.headers.get('X-Vsil-Command');
      document.getElementById('command').value = command;
      frame.dataset.command = command;
      frame.dataset.frames = String(Number(frame.dataset.frames) + 1);
      const renderMs = Number(response.headers.get('X-Vsil-Render-Ms'));
      const roundMs = performance.now() - sent;
      document.getElementById('readout').textContent =
          `frame ${renderMs.toFixed(0)} ms (round trip ${roundMs.toFixed(0)} ms)`;
      const warnings = response.headers.get('X-Vsil-Warnings');
      document.getElementById('error').textContent = warnings ? 'warning: ' + warnings : '';
    } else if (response.status !== 409) {  // 409: a newer view replaced it
      document.getElementById('error').textContent = (await response.text()).trim();
    }
  }).catch((e) => {
    document.getElementById('error').textContent = 'no answer from the server: ' + e;
  }).finally(() => {
    inFlight = false;
    if (dirty) requestFrame();
    else frame.dataset.busy = '0';
  });
}

// Shows a value set by the pointer or by another control in that option's control.
function reflect(key) {
  const input = document.getElementById('option-' + key);
  if (!input) return;
  const value = values[key];
  if (input.type === 'checkbox') {
    input.checked = value === 'on';
  } else {
    input.value = value === '' && input.type === 'range' ? input.min : value;
    if (input.type === 'range') input.nextSibling.textContent = value;
  }
}

// The CLI takes --width or --width-near with --width-far: setting one kind clears the other and
// gives a lone near (far) width its partner.
function setWidths(key, value) {
  const show = (k, v) => {
    values[k] = v;
    reflect(k);
  };
  if (key === 'width') {
    show('width_near', '');
    show('width_far', '');
  } else {
    show('width', '');
    const partner = key === 'width_near' ? 'width_far' : 'width_near';
    if (!values[partner]) show(partner, value);
  }
}

function set(key, value) {
  if (['width', 'width_near', 'width_far'].includes(key) && value) setWidths(key, value);
  values[key] = value;
  requestFrame();
}

function technique() {
  return table.techniques.find((t) => t.name === (values.technique || state.technique));
}

// A control for one option: a slider where the range is known, a picker for choices, a box
// for switches, a text field otherwise.
function control(option, range) {
  const label = document.createElement('label');
  label.title = option.help + (option.describe ? ' (' + option.describe + ')' : '');
  label.append(option.name);
  const shown = document.createElement('span');
  shown.className = 'value';
  let input;
  const current = values[option.key];
  const fallback = option.default === null || option.default === undefined ? '' : option.default;
  if (option.kind === 'choice' || table.presets[option.key]) {
    input = document.createElement('select');
    const names = option.kind === 'choice' ? option.choices : [''].concat(table.presets[option.key]);
    // The server's own value (a file it was started with) stays selectable.
    if (current && !names.includes(current)) names.push(current);
    for (const name of names) input.add(new Option(name || '(default)', name));
    input.value = current !== undefined ? current : fallback;
    input.onchange = () => set(option.key, input.value);
  } else if (option.kind === 'switch') {
    input = document.createElement('input');
    input.type = 'checkbox';
    input.checked = current === 'on';
    input.onchange = () => set(option.key, input.checked ? 'on' : 'off');
  } else if ((option.kind === 'number' || option.kind === 'integer') && range) {
    input = document.createElement('input');
    input.type = 'range';
    input.min = range[0];
    input.max = range[1];
    input.step = option.kind === 'integer' ? 1 : (range[1] - range[0]) / 200;
    const start = current !== undefined && current !== '' ? current
                : (typeof fallback === 'number' ? fallback : range[2]);
    input.value = start;
    shown.textContent = current !== undefined && current !== '' ? current : num(Number(start));
    input.oninput = () => {
      shown.textContent = num(Number(input.value));
      set(option.key, num(Number(input.value), 4));
    };
  } else {
    input = document.createElement('input');
    input.type = 'text';
    input.value = current !== undefined ? (Array.isArray(current) ? current.join(' ') : current)
                                        : (typeof fallback === 'string' ? fallback : '');
    input.placeholder = option.default_note || '';
    input.onchange = () => set(option.key, option.kind === 'list'
        ? input.value.split(/\s+/).filter((v) => v) : input.value);
  }
  input.id = 'option-' + option.key;
  label.append(input, shown);
  return label;
}

// Where a slider's ends are: the declared range, else what the data and the flag suggest.
function rangeOf(option) {
  const [lo, hi] = state.value_range;
  if (option.name === 'iso' || option.name === 'lmip-threshold') return [lo, hi, state.default_iso];
  if (option.name === 'material-eps') return [(hi - lo) / 1000, (hi - lo) / 4, (hi - lo) / 20];
  if (option.min !== null && option.max !== null) return [option.min, option.max, option.min];
  if (option.min !== null && option.min >= 0) return [option.min, option.min + 64, option.min];
  return null;
}

// The flags that shape lines and fills (the option table marks them line_flag): only techniques
// that draw lines use them (the others ignore them, with a warning).
function lineFlags() {
  return table.shared.filter((o) => o.line_flag);
}

// The shared flags the page shows as controls (the view itself is the drag and the wheel).
const widthRange = [1, 16, 1];
const sharedControls = {
  'width': widthRange, 'width-near': widthRange, 'width-far': widthRange,
  'fill': ['', 'none', 'flat', 'shaded', 'tone'], 'line-color': null, 'background': null, 'fill-color': null, 'size': null,
  'ortho': null, 'sampling': [0.25, 4, 1],
};

function buildControls() {
  const info = technique();
  document.getElementById('summary').textContent = info.summary;
  const own = document.getElementById('technique-options');
  own.replaceChildren(...info.options.map((o) => control(o, rangeOf(o))));
  const shared = document.getElementById('shared-options');
  shared.replaceChildren(...table.shared
      .filter((o) => o.name in sharedControls)
      .filter((o) => info.draws_lines || !o.line_flag)
      .map((o) => {
        const how = sharedControls[o.name];
        const choices = how && typeof how[0] === 'string' ? how : null;
        return control(Object.assign({}, o, {
          kind: o.kind === 'switch' ? 'switch' : (choices ? 'choice' : (how ? 'number' : 'text')),
          default: o.kind === 'switch' ? null : o.default, min: null, max: null,
          choices: choices || [], describe: '',
        }), choices ? null : how);
      }));
}

function chooseTechnique(name) {
  const previous = technique();
  values.technique = name;
  const next = technique();
  // Options of the last technique that this one does not declare: cleared, as the CLI would
  // refuse them.
  for (const option of previous.options) {
    if (!next.options.some((o) => o.name === option.name) && option.key in values) {
      values[option.key] = '';
    }
  }
  if (!next.draws_lines) for (const option of lineFlags()) {
    if (option.key in values) values[option.key] = '';
  }
  buildControls();
  requestFrame();
}

function view() {
  const [az, el] = (values.view || '30,20').split(',').map(Number);
  return { az, el };
}

function pixelOf(event) {
  const box = frame.getBoundingClientRect();
  return [Math.round((event.clientX - box.left) * frame.naturalWidth / box.width),
          Math.round((event.clientY - box.top) * frame.naturalHeight / box.height)];
}

function setUpPointer() {
  let drag = null;
  frame.addEventListener('pointerdown', (event) => {
    drag = { x: event.clientX, y: event.clientY, moved: false, shift: event.shiftKey,
             start: view(), sphere: (values.sphere_rotate || '0,0').split(',').map(Number) };
    frame.setPointerCapture(event.pointerId);
    frame.classList.add('dragging');
  });
  frame.addEventListener('pointermove', (event) => {
    if (!drag) return;
    const dx = event.clientX - drag.x, dy = event.clientY - drag.y;
    if (Math.abs(dx) + Math.abs(dy) >= 3) drag.moved = true;
    if (!drag.moved) return;
    if (drag.shift && technique().options.some((o) => o.name === 'sphere-rotate')) {
      // A sphere of weight 0 does not show: turning it turns it on, at half weight.
      if (!Number(values.sphere_weight)) {
        values.sphere_weight = '0.5';
        reflect('sphere_weight');
      }
      set('sphere_rotate', num(drag.sphere[0] + dx * 0.5, 1) + ',' +
                           num(Math.max(-90, Math.min(90, drag.sphere[1] - dy * 0.5)), 1));
      reflect('sphere_rotate');
    } else {
      const el = Math.max(-89, Math.min(89, drag.start.el + dy * 0.5));
      set('view', num(drag.start.az - dx * 0.5, 1) + ',' + num(el, 1));
    }
  });
  const end = (event) => {
    if (!drag) return;
    if (!drag.moved && technique().options.some((o) => o.name === 'cursor-pixel')) {
      set('cursor_pixel', pixelOf(event).join(','));
      reflect('cursor_pixel');
    }
    drag = null;
    frame.classList.remove('dragging');
  };
  frame.addEventListener('pointerup', end);
  frame.addEventListener('pointercancel', () => { drag = null; });
  frame.addEventListener('wheel', (event) => {
    event.preventDefault();
    const zoom = Number(values.zoom || 1) * Math.exp(-event.deltaY * 0.001);
    set('zoom', num(Math.max(0.05, Math.min(50, zoom)), 3));
  }, { passive: false });
}

async function start() {
  [table, state] = await Promise.all([
    fetch(api('api/options')).then((r) => r.json()),
    fetch(api('api/state')).then((r) => r.json()),
  ]);
  Object.assign(values, state.values);
  const picker = document.getElementById('technique');
  for (const t of table.techniques) picker.add(new Option(t.name, t.name));
  picker.value = values.technique || state.technique;
  picker.onchange = () => chooseTechnique(picker.value);
  buildControls();
  setUpPointer();
  document.getElementById('copy').onclick = () => {
    const field = document.getElementById('command');
    field.select();
    // The selection's copy works where the asynchronous clipboard is not granted (plain http
    // from another host, headless browsers).
    if (!document.execCommand('copy') && navigator.clipboard) {
      navigator.clipboard.writeText(field.value).catch(() => {});
    }
  };
  requestFrame();
}

start();
