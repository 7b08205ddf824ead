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

function showRunning(running) {
  const box = $('#running');
  box.replaceChildren();
  if (running.length === 0) {
    const p = document.createElement('p'); p.className = 'muted'; p.textContent = 'No job running.';
    box.appendChild(p);
    return;
  }
  for (const j of running) {
    const div = document.createElement('div'); div.className = 'job'; div.id = 'running-' + j.id;
    const title = document.createElement('div');
    title.textContent = '#' + j.id + ' ' + j.name + ' on ' + j.machine + ' — ' + j.machine_state +
      ', feed ' + j.override_percent + ' %, ' + j.executed + '/' + j.total + ' commands, ' +
      fmtSeconds(j.remaining_s) + ' left';
    const bar = document.createElement('progress'); bar.max = 1; bar.value = j.fraction;
    div.appendChild(title); div.appendChild(bar);
    button(div, 'Hold', () => control(j.id, 'hold'));
    button(div, 'Resume', () => control(j.id, 'resume'));
    button(div, 'Abort', () => { if (confirm('Abort job #' + j.id + '?')) control(j.id, 'abort'); });
    button(div, 'Feed −10 %', () => control(j.id, 'override', { percent: Math.max(10, j.override_percent - 10) }));
    button(div, 'Feed +10 %', () => control(j.id, 'override', { percent: Math.min(200, j.override_percent + 10) }));
    box.appendChild(div);
  }
}

function showPreview(job) {
  $('#preview-box').hidden = false;
  $('#preview-name').textContent = '#' + job.id + ' ' + job.name;
  $('#preview').src = '/api/jobs/' + job.id + '/files/plot.svg';
}

async function refreshJobs() {
  const r = await fetch('/api/jobs?limit=200');
  if (!r.ok) return;
  const data = await r.json();
  const tbody = $('#jobs tbody');
  tbody.replaceChildren();
  for (const j of data.jobs) {
    const tr = document.createElement('tr'); tr.id = 'job-' + j.id;
    cell(tr, j.id); cell(tr, j.name); cell(tr, j.state, 'state-' + j.state); cell(tr, j.priority);
    cell(tr, j.machine); cell(tr, fmtSeconds(j.planned_s)); cell(tr, j.message);
    const files = cell(tr, '');
    for (const f of ['plot.svg', 'plan.json', 'report.json', 'machine.log', j.input_file]) {
      const a = document.createElement('a'); a.href = '/api/jobs/' + j.id + '/files/' + f;
      a.textContent = f.replace('input.', '') + ' '; files.appendChild(a);
    }
    const actions = cell(tr, '');
    button(actions, 'Preview', () => showPreview(j));
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
  const r = await fetch('/api/jobs', { method: 'POST', headers: authHeaders(), body: new FormData(ev.target) });
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
