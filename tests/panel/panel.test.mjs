// The operator panel in headless Chromium on the simulated line: sign in, queue a job from the
// form, watch the progress counter move and a tile thumbnail appear, press Stop, and keep a
// screenshot. Starts tilejet-linesim and tilejetd like the C++ tests do: free ports (0),
// sockets and files in a fresh temp folder.
//
// node panel.test.mjs --linesim BIN --daemon BIN --cli BIN --map MAP --profile ICC
//                     --registers TOML --artifacts DIR
// $TILEJET_PANEL_SCREENSHOT: also copy the screenshot there (the README's docs/panel.png).
// Timeouts are generous: the same test runs against the sanitizer build.
import { spawn, execFileSync } from "node:child_process";
import { createRequire } from "node:module";
import fs from "node:fs";
import os from "node:os";
import path from "node:path";
import assert from "node:assert/strict";

const require = createRequire(path.join(process.env.PANEL_NODE_MODULES || ".", "x.js"));
const { chromium } = require("playwright-core");

const args = {};
for (let i = 2; i < process.argv.length; i += 2) args[process.argv[i].replace(/^--/, "")] = process.argv[i + 1];
for (const k of ["linesim", "daemon", "cli", "map", "profile", "registers", "artifacts"])
  if (!args[k]) throw new Error(`missing --${k}`);

const dir = fs.mkdtempSync(path.join(os.tmpdir(), "tjpanel-"));
const children = [];
const USER = "panel-operator";
const PASSWORD = "panel-operator-pw";

// Starts a process and resolves with its first stdout line, parsed (the "ready" line).
function start(bin, argv, log) {
  const child = spawn(bin, argv, { stdio: ["ignore", "pipe", fs.openSync(log, "a")] });
  children.push(child);
  return new Promise((resolve, reject) => {
    let text = "";
    const timer = setTimeout(() => reject(new Error(`${bin}: no ready line; see ${log}`)), 60000);
    child.stdout.on("data", (d) => {
      text += d;
      const nl = text.indexOf("\n");
      if (nl >= 0) { clearTimeout(timer); resolve(JSON.parse(text.slice(0, nl))); }
    });
    child.on("exit", (code) => reject(new Error(`${bin} exited with ${code}; see ${log}`)));
  });
}

function lineConfig(modbusPort) {
  return `[line]
tile_length_mm = 100
tile_pitch_mm = 200
photo_eye_mm = 50
heads_mm = 250
register_map = "${args.registers}"
[modbus]
host = "127.0.0.1"
port = ${modbusPort}
reconnect_min_ms = 20
reconnect_max_ms = 200
[gpio]
backend = "sim"
[sim]
gpio_socket = "${dir}/gpio.sock"
head_socket = "${dir}/heads.sock"
control_socket = "${dir}/control.sock"
speed_mm_s = 400
head_buffer_tiles = 2
`;
}

async function main() {
  const config = path.join(dir, "tilejet.toml");
  fs.writeFileSync(config, lineConfig(0));
  const sim = await start(args.linesim, ["--config", config, "--print-log", path.join(dir, "print.log")],
                          path.join(dir, "linesim.log"));
  // The password hash from the CLI, as an installer would make it (few iterations: a test).
  const entry = execFileSync(args.cli, ["passwd", USER, "--role", "operator", "--iterations", "1000"],
                             { input: PASSWORD + "\n" }).toString();
  fs.writeFileSync(config, lineConfig(sim.modbus_port) + `[colour]
output_profile = "${args.profile}"
[storage]
database = "${dir}/jobs.db"
previews = "${dir}/previews"
designs = "${path.dirname(args.map)}"
[api]
port = 0
[render]
threads = 1
queue_tiles = 4
dpi = 20
[print]
speed_mm_s = 400
min_speed_mm_s = 100
drain_timeout_s = 5
${entry}`);
  const daemon = await start(args.daemon, ["--config", config], path.join(dir, "tilejetd.log"));
  const url = `http://127.0.0.1:${daemon.api_port}/`;

  // A fresh profile folder each run (playwright passes it as --user-data-dir).
  const browser = await chromium.launchPersistentContext(path.join(dir, "chromium-profile"), {
    executablePath: "/usr/bin/chromium",
    args: ["--headless", "--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
           "--disable-background-networking", "--disable-component-update", "--disable-sync"],
    viewport: { width: 1400, height: 1100 },
    timeout: 120000,
  });
  try {
    const page = browser.pages()[0] || await browser.newPage();
    page.setDefaultTimeout(60000);
    page.on("pageerror", (e) => { throw e; });
    await page.goto(url);

    // A wrong password is refused with a message, the right one opens the panel.
    await page.fill("#signin-user", USER);
    await page.fill("#signin-password", "not-the-password");
    await page.click("#signin-button");
    await page.waitForFunction(() => document.getElementById("signin-error").textContent.length > 0);
    assert.ok((await page.isVisible("#panel")) === false, "panel shown after a wrong password");
    await page.fill("#signin-password", PASSWORD);
    await page.click("#signin-button");
    await page.waitForSelector("#panel", { state: "visible" });
    assert.match(await page.textContent("#who"), /panel-operator \(operator\)/);
    // Cookies the page's scripts could read would be readable by injected scripts too.
    assert.equal(await page.evaluate(() => document.cookie), "");

    // Queue a job from the form, with the design the daemon lists.
    await page.waitForFunction(() => document.querySelectorAll("#f-design option[value$='.tjmap']").length > 0);
    await page.selectOption("#f-design", { value: path.basename(args.map) });
    // The design's resolution is shown beside its name and taken into the form.
    const label = await page.$eval("#f-design", (s) => s.selectedOptions[0].textContent);
    if (!/\(\d+ dpi\)$/.test(label)) throw new Error(`design shown without its dpi: ${label}`);
    if (!(Number(await page.inputValue("#f-dpi")) > 0)) throw new Error("job form took no dpi from the design");
    await page.fill("#f-seed", "7");
    await page.fill("#f-count", "400");
    await page.fill("#f-tile", "200x200");
    await page.click("#f-submit");
    await page.waitForFunction(() => /queued/.test(document.getElementById("submit-error").textContent));

    // The counter moves (twice, so it is progress and not a single update), from events.
    const printed = async () => Number((await page.textContent("#printed")).replace(/[^0-9]/g, "") || 0);
    await page.waitForFunction(() => Number(document.getElementById("printed").textContent.replace(/[^0-9]/g, "")) > 0, null, { timeout: 120000 });
    const first = await printed();
    await page.waitForFunction((n) => Number(document.getElementById("printed").textContent.replace(/[^0-9]/g, "")) > n, first, { timeout: 120000 });
    assert.equal(await page.textContent("#state"), "printing");

    // A thumbnail of a next tile has loaded (a decoded image, not just an <img>).
    await page.waitForFunction(() => [...document.querySelectorAll("img.tile-thumb")].some((i) => i.complete && i.naturalWidth > 0), null, { timeout: 120000 });
    await page.waitForFunction(() => { const w = document.getElementById("wall"); return !w.hidden && w.complete && w.naturalWidth > 0; }, null, { timeout: 120000 });

    fs.mkdirSync(args.artifacts, { recursive: true });
    const shot = path.join(args.artifacts, "panel.png");
    await page.screenshot({ path: shot, fullPage: true });
    if (process.env.TILEJET_PANEL_SCREENSHOT) fs.copyFileSync(shot, process.env.TILEJET_PANEL_SCREENSHOT);

    // Stop: the job ends cancelled and the line leaves printing.
    await page.click("#btn-stop");
    await page.waitForFunction(() => [...document.querySelectorAll("#jobs td")].some((td) => td.textContent === "cancelled"), null, { timeout: 120000 });
    await page.screenshot({ path: path.join(args.artifacts, "panel-stopped.png"), fullPage: true });
    const stoppedAt = await printed();
    assert.ok(stoppedAt < 400, `the job ran to the end (${stoppedAt}) instead of stopping`);
    console.log(`panel test passed: printed ${first} then more, stopped at ${stoppedAt}; screenshot ${shot}`);
  } finally {
    await browser.close();
  }
}

let failed = false;
try {
  await main();
} catch (e) {
  failed = true;
  console.error("panel test FAILED:", e);
  for (const log of ["tilejetd.log", "linesim.log"]) {
    const p = path.join(dir, log);
    if (fs.existsSync(p)) console.error(`--- ${log} (last lines)\n` + fs.readFileSync(p, "utf8").split("\n").slice(-30).join("\n"));
  }
} finally {
  for (const c of children.reverse()) c.kill("SIGTERM");
  await new Promise((r) => setTimeout(r, 1500));
  for (const c of children) if (c.exitCode === null && c.signalCode === null) c.kill("SIGKILL");
  fs.rmSync(dir, { recursive: true, force: true });
}
process.exit(failed ? 1 : 0);
