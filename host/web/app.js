// The workshop page: live machine and job state over server-sent events (/api/events),
// the queue from /api/jobs, uploads and job controls with the token kept in this browser.
'use strict';

const $ = (sel) => document.querySelector(sel);
const tokenInput = $('#token');
tokenInput.value = localStorage.getItem('engraver-token') || '';
tokenInput.addEventListener('change', () => localStorage.setItem('engraver-token', tokenInput.value.trim()));

function authHeaders() { return { 'Authorization': 'Bearer ' + tokenInput.value.trim() }; }

// Text into an element, never HTML: job names come from uploads.
function cell(row, text, cls) {
  const td = document.createElement('td');
  td.textContent = text === undefined || text === null ? '' : String(text);
  if (cls) td.className = cls;
  row.appendChild(td);
  return td;
}

function fmtSeconds(s) {
  s = Math.max(0, Math.round(s));
  return Math.floor(s / 60) + ':' + String(s % 60).padStart(2, '0');
}

async function control(id, action, extra) {
  const body = Object.assign({ action: action }, extra || {});
  const r = await fetch('/api/jobs/' + id + '/control', {
    method: 'POST', headers: Object.assign({ 'Content-Type': 'application/json' }, authHeaders()),
    body: JSON.stringify(body) });
  if (!r.ok) alert((await r.json()).error || r.statusText);
  refreshJobs();
}

function button(parent, label, onClick) {
  const b = document.createElement('button');
  b.textContent = label;
  b.addEventListener('click', onClick);
  parent.appendChild(b);
}

function showMachines(machines) {
  const tbody = $('#machines tbody');
  tbody.replaceChildren();
  for (const m of machines) {
    const tr = document.createElement('tr');
    cell(tr, m.name); cell(tr, m.address); cell(tr, m.link, 'link-' + m.link); cell(tr, m.state);
    cell(tr, m.position_mm ? m.position_mm.map((v) => v.toFixed(2)).join(', ') : '');
    cell(tr, m.work_mm[0] + ' x ' + m.work_mm[1]); cell(tr, m.tags.join(', '));
    cell(tr, m.job ? '#' + m.job : '');
    tbody.appendChild(tr);
  }
}

// ---- Live preview of a running job: its path (GET /api/jobs/N/path, in mm), the part
// executed so far and the tool where the machine reports it (from the event stream).
const SVG = 'http://www.w3.org/2000/svg';
const livePaths = new Map();  // job id -> { svg, path, done, shown, full }

function svgEl(name, attrs) {
  const e = document.createElementNS(SVG, name);
  for (const [k, v] of Object.entries(attrs || {})) e.setAttribute(k, v);
  return e;
}

function pointsAttr(points) { return points.map((p) => p[0] + ',' + p[1]).join(' '); }

// The first `mm` of a piece's polyline.
function pieceUpTo(piece, mm) {
  const out = [piece.points_mm[0]];
  let along = piece.start_mm;
  for (let i = 1; i < piece.points_mm.length; ++i) {
    const a = piece.points_mm[i - 1], b = piece.points_mm[i];
    const len = Math.hypot(b[0] - a[0], b[1] - a[1]);
    if (along + len >= mm) {
      const t = len > 0 ? (mm - along) / len : 0;
      out.push([a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1])]);
      return out;
    }
    along += len;
    out.push(b);
  }
  return out;
}

function livePreview(j) {
  let live = livePaths.get(j.id);
  if (!live) {
    // y up as on the machine: everything in a group mirrored about the x axis.
    const svg = svgEl('svg', { class: 'live-path', id: 'live-path-' + j.id });
    const g = svgEl('g', { transform: 'scale(1,-1)' });
    const plan = svgEl('g', { class: 'plan' });
    const done = svgEl('g', { class: 'done' });
    const current = svgEl('polyline', { class: 'cut current' });
    const tool = svgEl('circle', { class: 'tool', r: '1' });
    tool.style.display = 'none';
    done.appendChild(current);
    g.append(plan, done, tool);
    svg.appendChild(g);
    live = { svg: svg, plan: plan, done: done, current: current, tool: tool, path: null,
      full: 0, last: null };
    livePaths.set(j.id, live);
    fetch('/api/jobs/' + j.id + '/path').then((r) => r.ok ? r.json() : null).then((path) => {
      if (!path) { livePaths.delete(j.id); return; }  // not cutting yet: asked again later
      drawPlan(live, path);
      if (live.last) updateLive(live, live.last);
    }).catch(() => livePaths.delete(j.id));
  }
  live.last = j;
  if (live.path) updateLive(live, j);
  return live.svg;
}

function drawPlan(live, path) {
  live.path = path;
  let x0 = Infinity, y0 = Infinity, x1 = -Infinity, y1 = -Infinity;
  for (const piece of path.pieces) {
    for (const [x, y] of piece.points_mm) {
      x0 = Math.min(x0, x); y0 = Math.min(y0, y); x1 = Math.max(x1, x); y1 = Math.max(y1, y);
    }
    live.plan.appendChild(svgEl('polyline', { class: piece.pen_down ? 'cut' : 'travel',
      points: pointsAttr(piece.points_mm) }));
  }
  if (x0 > x1) { x0 = y0 = 0; x1 = y1 = 1; }
  const m = Math.max(2, 0.03 * Math.max(x1 - x0, y1 - y0));
  live.svg.setAttribute('viewBox', [x0 - m, -(y1 + m), x1 - x0 + 2 * m, y1 - y0 + 2 * m].join(' '));
  live.tool.setAttribute('r', String(Math.max(0.5, m / 2)));
}

// The executed part: pieces done whole are added once; the current one is redrawn.
function updateLive(live, j) {
  const pieces = live.path.pieces;
  const mm = j.executed_mm;
  while (live.full < pieces.length &&
         pieces[live.full].start_mm + pieces[live.full].length_mm <= mm) {
    const piece = pieces[live.full++];
    live.done.insertBefore(svgEl('polyline', { class: piece.pen_down ? 'cut' : 'travel',
      points: pointsAttr(piece.points_mm) }), live.current);
  }
  const now = live.full < pieces.length ? pieces[live.full] : null;
  live.current.setAttribute('points', now && mm > now.start_mm ? pointsAttr(pieceUpTo(now, mm)) : '');
  live.current.setAttribute('class', now && !now.pen_down ? 'travel current' : 'cut current');
  live.svg.dataset.executedMm = String(mm);
  if (j.position_mm) {
    live.tool.style.display = '';
    live.tool.setAttribute('cx', String(j.position_mm[0]));
    live.tool.setAttribute('cy', String(j.position_mm[1]));
  }
}

function showRunning(running) {
  const box = $('#running');
  box.replaceChildren();
  for (const id of [...livePaths.keys()]) {
    if (!running.some((j) => j.id === id)) livePaths.delete(id);
  }
  if (running.length === 0) {
    const p = document.createElement('p'); p.className = 'muted'; p.textContent = 'No job running.';
    box.appendChild(p);
    return;
  }
  for (const j of running) {
    const div = document.createElement('div'); div.className = 'job'; div.id = 'running-' + j.id;
    const title = document.createElement('div');
    title.textContent = '#' + j.id + ' ' + j.name + ' on ' + j.machine + ' — ' + j.machine_state +
      (j.machine_state === 'planning' ? '…' : ', feed ' + j.override_percent + ' %, ' +
        j.executed + '/' + j.total + ' commands, ' + j.executed_mm.toFixed(1) + ' of ' +
        j.path_mm.toFixed(1) + ' mm, ' + fmtSeconds(j.remaining_s) + ' left');
    const bar = document.createElement('progress'); bar.max = 1; bar.value = j.fraction;
    div.appendChild(title); div.appendChild(bar);
    if (j.probe) {  // a probe-first board: the probe clip, then the touches
      const ask = document.createElement('p'); ask.className = 'probe'; ask.id = 'probe-' + j.id;
      const aborting = j.machine_state === 'aborting';  // the tool going up, then it ends
      ask.textContent = aborting ? 'Aborted: the tool goes up, nothing is cut.'
        : j.probe.stage === 'probe_clip' ? 'Put the probe clip on the blank, the spindle off.'
        : 'Probing the blank: ' + j.probe.touches + ' of ' + j.probe.planned + ' touches';
      div.appendChild(ask);
      if (j.probe.stage === 'probe_clip' && !aborting) button(ask, 'Clip on: probe', () => control(j.id, 'probe_ready'));
    }
    if (j.machine_state !== 'planning') div.appendChild(livePreview(j));
    button(div, 'Hold', () => control(j.id, 'hold'));
    button(div, 'Resume', () => control(j.id, 'resume'));
    button(div, 'Abort', () => { if (confirm('Abort job #' + j.id + '?')) control(j.id, 'abort'); });
    button(div, 'Feed −10 %', () => control(j.id, 'override', { percent: Math.max(10, j.override_percent - 10) }));
    button(div, 'Feed +10 %', () => control(j.id, 'override', { percent: Math.min(200, j.override_percent + 10) }));
    box.appendChild(div);
  }
}

function showPreview(job, file) {
  $('#preview-box').hidden = false;
  $('#preview-name').textContent = '#' + job.id + ' ' + job.name + (file ? ' (height map)' : '');
  $('#preview').src = '/api/jobs/' + job.id + '/files/' + (file || 'plot.svg');
}

async function refreshJobs() {
  const r = await fetch('/api/jobs?limit=200');
  if (!r.ok) return;
  const data = await r.json();
  const tbody = $('#jobs tbody');
  tbody.replaceChildren();
  for (const j of data.jobs) {
    const tr = document.createElement('tr'); tr.id = 'job-' + j.id;
    cell(tr, j.id); cell(tr, j.name);
    cell(tr, j.stage === 'planning' ? 'running (planning)' : j.state, 'state-' + j.state);
    cell(tr, j.priority);
    cell(tr, j.machine); cell(tr, fmtSeconds(j.planned_s)); cell(tr, j.message);
    const files = cell(tr, '');
    const kept = ['plot.svg', 'plan.json', 'report.json', 'machine.log', j.input_file];
    if (j.height_map) kept.push('heightmap.svg', 'heightmap.json');
    for (const f of kept) {
      const a = document.createElement('a'); a.href = '/api/jobs/' + j.id + '/files/' + f;
      a.textContent = f.replace('input.', '') + ' '; files.appendChild(a);
    }
    const actions = cell(tr, '');
    button(actions, 'Preview', () => showPreview(j));
    if (j.height_map) button(actions, 'Height map', () => showPreview(j, 'heightmap.svg'));
    if (j.state === 'queued') button(actions, 'Cancel', () => control(j.id, 'cancel'));
    if (['interrupted', 'aborted', 'failed'].includes(j.state)) {
      button(actions, 'Re-queue', () => control(j.id, 'requeue'));
    }
    if (j.state === 'interrupted' && j.resume_curve >= 0) {
      button(actions, 'Continue', () => control(j.id, 'continue'));
    }
    tbody.appendChild(tr);
  }
}

$('#upload').addEventListener('submit', async (ev) => {
  ev.preventDefault();
  const out = $('#upload-result');
  out.textContent = 'uploading…'; out.className = '';
  // Several files chosen together are one board (copper, drill, outline): one request.
  // A drawing takes no board fields, a board no feed (the server refuses what does not apply).
  const form = new FormData(ev.target);
  const files = $('#file').files;
  const drawing = files.length === 1 && /\.(dxf|ngc|nc|gcode|tap|g)$/i.test(files[0].name);
  const boardFields = ['side', 'tool_width_mm', 'allow_narrow_gaps', 'probe_first'];
  for (const k of drawing ? boardFields : ['feed_mm_s']) form.delete(k);
  const r = await fetch('/api/jobs', { method: 'POST', headers: authHeaders(), body: form });
  const body = await r.json().catch(() => ({ error: r.statusText }));
  if (r.ok) {
    out.textContent = 'queued as #' + body.id; out.className = 'ok';
    showPreview(body);
  } else {
    out.textContent = body.error || r.statusText; out.className = 'error';
  }
  refreshJobs();
});

let jobsVersion = -1;
function connect() {
  const events = new EventSource('/api/events');
  events.onopen = () => { $('#live').textContent = 'live'; $('#live').className = 'badge on'; };
  events.onerror = () => { $('#live').textContent = 'reconnecting'; $('#live').className = 'badge off'; };
  events.onmessage = (ev) => {
    const s = JSON.parse(ev.data);
    showMachines(s.machines);
    showRunning(s.running);
    if (s.jobs_version !== jobsVersion) { jobsVersion = s.jobs_version; refreshJobs(); }
  };
}
connect();
refreshJobs();
