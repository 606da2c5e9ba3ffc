// Runs MJCF files in current MuJoCo (mujoco-js) with plain mj_step, as a client driving them by their
// actuators and equalities would, and prints one body's state at chosen steps, for comparing contact
// behaviour with MuJoCo 2.2.2 (contacts_test.cpp does the same in 2.2.2). Usage:
//   node run_contacts.mjs BODY STEP[,STEP...] FILE... [ctrl:ACTUATOR=VALUE | eq:EQUALITY=VALUE]...
// `ctrl:` sets an actuator's control, `eq:` the first number of an equality's data (a joint equality's
// target), once before the first step. Prints per file `AT FILE STEP x y z vx vy vz wx wy wz NCON` for each
// step asked for (the body's position, its free joint's velocity: linear in world axes, angular in the
// body's; NCON the most contacts seen so far), or `ERR FILE MESSAGE`. One process for several files: the
// module takes a while to start.
import fs from 'node:fs';
import loadMujoco from 'mujoco-js';

const [bodyName, stepList, ...rest] = process.argv.slice(2);
const settings = rest.filter((a) => /^(ctrl|eq):/.test(a)), files = rest.filter((a) => !/^(ctrl|eq):/.test(a));
let printed = '';
const mujoco = await loadMujoco({print: (t) => { printed += t + ' '; }, printErr: (t) => { printed += t + ' '; }});

function id(m, type, name) {
  const found = mujoco.mj_name2id(m, mujoco.mjtObj[type].value, name);
  if (found < 0) throw new Error(`no ${type} named ${name}`);
  return found;
}

function run(file) {
  let m = null, d = null;
  try {
    mujoco.FS.writeFile('/model.xml', fs.readFileSync(file));
    m = mujoco.MjModel.loadFromXML('/model.xml');
    if (!m) throw new Error('load failed');
    d = new mujoco.MjData(m);
    for (const s of settings) {
      const [, kind, name, value] = s.match(/^(ctrl|eq):(.+)=(.+)$/);
      if (kind === 'ctrl') d.ctrl[id(m, 'mjOBJ_ACTUATOR', name)] = Number(value);
      else m.eq_data[mujoco.mjNEQDATA * id(m, 'mjOBJ_EQUALITY', name)] = Number(value);
    }
    const body = id(m, 'mjOBJ_BODY', bodyName);
    const dof = m.jnt_dofadr[m.body_jntadr[body]];
    const wanted = stepList.split(',').map(Number);
    mujoco.mj_forward(m, d);
    let ncon = d.ncon;
    for (let k = 0; k <= Math.max(...wanted); ++k) {
      if (wanted.includes(k)) {
        const state = [...Array.from(d.xpos.slice(3 * body, 3 * body + 3)), ...Array.from(d.qvel.slice(dof, dof + 6))];
        console.log(`AT ${file} ${k} ${state.map((v) => v.toPrecision(17)).join(' ')} ${ncon}`);
      }
      mujoco.mj_step(m, d);
      ncon = Math.max(ncon, d.ncon);
    }
  } catch (e) {
    console.log(`ERR ${file} ${(printed + (e && e.message ? e.message : String(e))).replace(/\s+/g, ' ')}`);
  } finally {
    if (d) d.delete();
    if (m) m.delete();
  }
}

for (const file of files) {
  printed = '';
  run(file);
}
