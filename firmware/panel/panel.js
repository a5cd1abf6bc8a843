// The operator panel: signs in, then follows the line through /api/events (EventSource
// reconnects by itself) and sends commands with the session's CSRF token. No framework and no
// build step: the daemon serves this file as it is.
"use strict";

const $ = (id) => document.getElementById(id);
let session = null;  // {user, role, csrf}
let events = null;
let shownNext = "";
let wallShown = "";
let wallTimer = null;

async function api(method, path, body) {
  const headers = {};
  if (session && method !== "GET") headers["X-CSRF-Token"] = session.csrf;
  if (body !== undefined) headers["Content-Type"] = "application/json";
  const res = await fetch(path, {
    method, headers, credentials: "same-origin",
    body: body === undefined ? undefined : JSON.stringify(body),
  });
  const data = await res.json().catch(() => ({}));
  if (res.status === 401 && path !== "/api/session") showSignIn();
  if (!res.ok) throw new Error(data.error || `HTTP ${res.status}`);
  return data;
}

function showSignIn(message) {
  session = null;
  if (events) events.close();
  events = null;
  $("panel").hidden = true;
  $("signout").hidden = true;
  $("who").textContent = "";
  $("signin").hidden = false;
  $("signin-error").textContent = message || "";
  setState(null);
}

async function signedIn(s) {
  session = s;
  $("signin").hidden = true;
  $("panel").hidden = false;
  $("signout").hidden = false;
  $("who").textContent = `${s.user} (${s.role})`;
  // A viewer sees everything and controls nothing.
  for (const el of document.querySelectorAll(".control")) el.hidden = s.role === "viewer";
  connect();
  loadChoices();
}

function connect() {
  if (events) events.close();
  events = new EventSource("/api/events");
  events.addEventListener("open", () => { $("link").hidden = true; });
  events.addEventListener("status", (e) => renderStatus(JSON.parse(e.data)));
  events.addEventListener("jobs", (e) => renderJobs(JSON.parse(e.data)));
  events.addEventListener("error", async () => {
    $("link").hidden = false;
    // CONNECTING: the browser retries by itself. CLOSED: the server refused the stream
    // (signed out, or too many panels open): find out which.
    if (events.readyState !== EventSource.CLOSED) return;
    try {
      await api("GET", "/api/session");
      setTimeout(connect, 3000);
    } catch (_) { /* api() showed the sign-in */ }
  });
}

function setState(state) {
  const el = $("state");
  el.className = "state state-" + (state || "unknown");
  el.textContent = state || "—";
}

function fmt(n) { return n === undefined || n === null ? "—" : Number(n).toLocaleString("en"); }

function renderStatus(s) {
  if (s.error) { $("reason").textContent = s.error; return; }
  setState(s.state);
  $("reason").textContent = s.reason || "";
  $("speed").textContent = s.conveyor_running
    ? `${fmt(s.speed_mm_s || s.speed_setpoint_mm_s)} mm/s` : "stopped";
  $("estop").textContent = s.estop_latched ? "PRESSED" : "clear";
  $("rate").textContent = s.rate_tiles_per_min ? s.rate_tiles_per_min.toFixed(1) : "0";
  $("btn-ack").hidden = !(s.estop_latched || s.state === "e-stop") || session.role === "viewer";

  const faults = $("faults");
  faults.replaceChildren(...(s.faults || []).map((f) => {
    const li = document.createElement("li");
    li.className = f.severity;
    const title = document.createElement("strong");
    title.textContent = f.title;
    li.append(title, document.createTextNode(f.action));
    return li;
  }));

  const job = s.job;
  $("job-name").textContent = job ? job.name : "— none";
  const pct = job && job.tiles ? Math.min(100, (100 * job.printed) / job.tiles) : 0;
  $("progress-bar").style.width = pct + "%";
  $("progress-text").textContent = job ? `${fmt(job.printed)} / ${fmt(job.tiles)}` : "";
  $("printed").textContent = job ? fmt(job.printed) : "—";
  $("remaining").textContent = job ? fmt(job.remaining) : "—";
  $("missed").textContent = job ? fmt(job.missed_line_tiles) : fmt(s.line_tiles_missed);
  $("spoiled").textContent = job ? fmt(job.spoiled) : fmt(s.spoiled);
  $("btn-pause").disabled = s.state !== "printing" && s.state !== "ready";
  $("btn-resume").disabled = s.state === "printing";
  $("btn-stop").disabled = !job;

  renderNext(job, s.next_tiles || []);
  renderWall(s.wall);
}

function renderNext(job, next) {
  const key = job ? `${job.id}:${next.join(",")}` : "";
  if (key === shownNext) return;
  shownNext = key;
  const box = $("next-tiles");
  if (!job || next.length === 0) {
    box.innerHTML = '<p class="empty">No job on the line.</p>';
    return;
  }
  box.replaceChildren(...next.map((k) => {
    const fig = document.createElement("figure");
    const img = document.createElement("img");
    img.src = `/api/jobs/${job.id}/tiles/${k}.png?size=160`;
    img.alt = `tile ${k}`;
    img.className = "tile-thumb";
    const cap = document.createElement("figcaption");
    cap.textContent = `tile ${k}`;
    fig.append(img, cap);
    return fig;
  }));
}

// At most one wall picture every few seconds: it is the most expensive thing on the page.
function renderWall(wall) {
  if (!wall) return;
  const key = `${wall.job}:${wall.printed}`;
  if (key === wallShown || wallTimer) return;
  wallTimer = setTimeout(() => {
    wallTimer = null;
    wallShown = key;
    const img = $("wall");
    img.src = `/api/wall.png?tiles=12&size=640&v=${encodeURIComponent(key)}`;
    img.hidden = false;
    $("wall-empty").hidden = true;
    $("wall-caption").textContent = `${wall.name}, last printed tiles`;
  }, wallShown ? 3000 : 0);
}

function renderJobs(jobs) {
  $("jobs").replaceChildren(...jobs.slice(0, 12).map((j) => {
    const tr = document.createElement("tr");
    const design = j.map.split("/").pop();
    for (const [text, cls] of [[j.name, ""], [j.status, "status-" + j.status],
                               [`${fmt(j.printed)} / ${fmt(j.tiles)}`, ""], [design, ""]]) {
      const td = document.createElement("td");
      td.textContent = text;
      if (cls) td.className = cls;
      tr.append(td);
    }
    return tr;
  }));
}

async function loadChoices() {
  try {
    const [designs, profiles] = await Promise.all([api("GET", "/api/designs"), api("GET", "/api/profiles")]);
    const design = $("f-design");
    // A design prints at its own resolution: shown beside its name and put in the form.
    design.replaceChildren(...designs.map((d) => {
      const o = new Option(d.dpi ? `${d.name} (${d.dpi} dpi)` : d.name, d.name);
      o.dataset.dpi = d.dpi || "";
      return o;
    }));
    if (designs.length === 0) design.append(new Option("(no designs in [storage] designs)", ""));
    const takeDpi = () => {
      const chosen = design.selectedOptions[0];
      $("f-dpi").value = chosen ? chosen.dataset.dpi || "" : "";
    };
    design.onchange = takeDpi;
    takeDpi();
    const profile = $("f-profile");
    profile.replaceChildren(new Option("line default", ""),
                            ...profiles.map((p) => new Option(p.name, p.name)));
  } catch (e) {
    $("submit-error").textContent = e.message;
  }
}

async function command(name) {
  $("command-error").textContent = "";
  try {
    await api("POST", `/api/line/${name}`);
  } catch (e) {
    $("command-error").textContent = e.message;
  }
}

function wire() {
  $("signin-form").addEventListener("submit", async (e) => {
    e.preventDefault();
    try {
      const s = await api("POST", "/api/session",
                          { user: $("signin-user").value, password: $("signin-password").value });
      $("signin-password").value = "";
      signedIn(s);
    } catch (err) {
      $("signin-error").textContent = err.message;
    }
  });
  $("signout").addEventListener("click", async () => {
    try { await api("DELETE", "/api/session"); } catch (_) { /* signed out either way */ }
    showSignIn("Signed out.");
  });
  $("btn-resume").addEventListener("click", () => command("resume"));
  $("btn-pause").addEventListener("click", () => command("pause"));
  $("btn-stop").addEventListener("click", () => command("stop"));
  $("btn-ack").addEventListener("click", () => command("acknowledge"));
  $("submit-form").addEventListener("submit", async (e) => {
    e.preventDefault();
    $("submit-error").textContent = "";
    $("submit-error").classList.remove("ok");
    const body = {
      map: $("f-design").value,
      seed: Number($("f-seed").value),
      tiles: Number($("f-count").value),
      tile_mm: $("f-tile").value,
      layout: $("f-layout").value,
    };
    if ($("f-profile").value) body.profile = $("f-profile").value;
    if ($("f-dpi").value) body.dpi = Number($("f-dpi").value);
    if (body.layout === "wall") body.wall_width = Number($("f-wall-width").value);
    try {
      const job = await api("POST", "/api/jobs", body);
      $("submit-error").textContent = `${job.name} queued.`;
      $("submit-error").classList.add("ok");
    } catch (err) {
      $("submit-error").textContent = err.message;
    }
  });
}

wire();
api("GET", "/api/session").then(signedIn).catch(() => showSignIn());
