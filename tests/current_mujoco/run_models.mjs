// Loads MJCF files in current MuJoCo (the official WebAssembly build, pinned in package.json) and prints one
// line per file: `OK FILE NBODY NCON` then the body poses (xpos, xquat) after mj_forward and after STEPS
// mj_step calls, NCON the most contacts seen; or `ERR FILE MESSAGE`. Usage: node run_models.mjs STEPS FILE...
// The module has no host file system: each XML, the files it includes and the meshes and textures it names are
// copied into its in-memory file system at their own absolute paths, so relative paths resolve as on disk.
import fs from 'node:fs';
import path from 'node:path';
import loadMujoco from 'mujoco-js';

const steps = Number(process.argv[2]);
const files = process.argv.slice(3);
let printed = '';
const mujoco = await loadMujoco({print: (t) => { printed += t + '\n'; }, printErr: (t) => { printed += t + '\n'; }});

function mkdirs(dir) {
  let at = '';
  for (const part of dir.split('/').filter((p) => p)) {
    at += '/' + part;
    try { mujoco.FS.mkdir(at); } catch (e) { /* exists */ }
  }
}

// Copies `file` and everything its file="..." attributes name (relative to its folder) into the module.
function copyIn(file, seen = new Set()) {
  if (seen.has(file)) return;
  seen.add(file);
  const bytes = fs.readFileSync(file);
  mkdirs(path.dirname(file));
  mujoco.FS.writeFile(file, bytes);
  if (!file.endsWith('.xml')) return;
  for (const match of bytes.toString('utf8').matchAll(/\bfile="([^"]+)"/g)) {
    const named = path.resolve(path.dirname(file), match[1]);
    if (fs.existsSync(named)) copyIn(named, seen);
  }
}

// MuJoCo's exceptions escape the module uncaught; both its error types begin with their message (a C string).
function errorText(e) {
  if (e && typeof e.excPtr === 'number') {
    const heap = new Uint8Array(heapBuffer());
    let end = e.excPtr;
    while (end < heap.length && heap[end] !== 0) ++end;
    return `${e.name}: ${new TextDecoder().decode(heap.subarray(e.excPtr, end))}`;
  }
  return printed.trim() || String(e);
}

// The module exports no heap view; any embind array (here a scratch model's data) lies over the heap.
mujoco.FS.writeFile('/scratch.xml', '<mujoco><worldbody><body><freejoint/><geom size="1"/></body></worldbody></mujoco>');
const scratchModel = mujoco.MjModel.loadFromXML('/scratch.xml');
const scratchData = new mujoco.MjData(scratchModel);
function heapBuffer() {
  return scratchData.xpos.buffer;
}

function poses(d) {
  return [...Array.from(d.xpos), ...Array.from(d.xquat)].map((v) => v.toPrecision(17)).join(' ');
}

for (const file of files) {
  printed = '';
  let m = null, d = null;
  try {
    copyIn(path.resolve(file));
    m = mujoco.MjModel.loadFromXML(path.resolve(file));
    if (!m) throw new Error('load failed');
    d = new mujoco.MjData(m);
    mujoco.mj_forward(m, d);
    const start = poses(d);
    let ncon = d.ncon;
    for (let k = 0; k < steps; ++k) {
      mujoco.mj_step(m, d);
      ncon = Math.max(ncon, d.ncon);
    }
    console.log(`OK ${file} ${m.nbody} ${ncon} ${start} ${poses(d)}`);
  } catch (e) {
    console.log(`ERR ${file} ${errorText(e).replace(/\s+/g, ' ')}`);
  } finally {
    if (d) d.delete();
    if (m) m.delete();
  }
}
