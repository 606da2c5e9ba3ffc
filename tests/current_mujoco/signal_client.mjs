// A reference client of the signal manifest (docs/signals.schema.json) on npm's mujoco-js: drives a model
// openplx2mjcf emitted by OpenPLX signal names from its OUT.signals.json alone, without the C++ runtime.
// Each quantity is applied as its kind's description in the schema says after "Apply:", and the work it says
// after "Each step:" is done in afterStep(). What only the runtime computes (signals marked `runtime`, the `laws`) runs as the MJCF's static
// stand-in: such a handle has exact = false and the client's warnings say why.
//
//   const client = new SignalClient(mujoco, model, data, JSON.parse(manifestText));
//   client.input('push').set(20);
//   mujoco.mj_step(model, data); client.afterStep();
//   const angle = client.output('pole_angle').read();

export const KNOWN_FORMAT_VERSION = 1;

export class ClientError extends Error {}

const OBJECT_TYPES = {
  actuator: 'mjOBJ_ACTUATOR', joint: 'mjOBJ_JOINT', body: 'mjOBJ_BODY', site: 'mjOBJ_SITE',
  equality: 'mjOBJ_EQUALITY', tendon: 'mjOBJ_TENDON', sensor: 'mjOBJ_SENSOR',
};
const COMPOSED = new Set(['composite', 'broadcast', 'affine']);
const CONSTRAINT_ROWS = {
  joint_limit_force: 'mjCNSTR_LIMIT_JOINT', equality_force: 'mjCNSTR_EQUALITY',
  tendon_limit_force: 'mjCNSTR_LIMIT_TENDON', motor_force: 'mjCNSTR_FRICTION_TENDON',
};

// Numbers JSON cannot hold arrive as strings.
function num(v) {
  return v === 'inf' ? Infinity : v === '-inf' ? -Infinity : v === 'nan' ? NaN : v;
}

function poly(c, x) {
  let y = 0;
  for (let p = c.length - 1; p >= 0; --p) y = y * x + c[p];
  return y;
}

// The x with poly(c, x) = y, by Newton's method from y / c[1], kept within [low, high] when low < high
// (the polynomial is monotonic over a steering column's reach).
function polyInverse(c, y, low, high) {
  if (c.length === 0) return y;
  if (c.length < 2 || c[1] === 0) return 0;
  let x = (y - c[0]) / c[1];
  for (let k = 0; k < 60; ++k) {
    let slope = 0;
    for (let p = c.length - 1; p >= 1; --p) slope = slope * x + p * c[p];
    if (slope === 0 || !Number.isFinite(slope)) break;
    const dx = (poly(c, x) - y) / slope;
    x -= dx;
    if (low < high) x = Math.min(high, Math.max(low, x));
    if (Math.abs(dx) <= 1e-15 * Math.max(1, Math.abs(x))) break;
  }
  return x;
}

// Roll, pitch, yaw of a row-major rotation matrix: R = Rz(yaw) Ry(pitch) Rx(roll).
function rpy(r) {
  return [Math.atan2(r[7], r[8]), Math.asin(Math.min(1, Math.max(-1, -r[6]))), Math.atan2(r[3], r[0])];
}

function quatToMat(q) {
  const [w, x, y, z] = q;
  return [1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y),
          2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x),
          2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)];
}

function cross(a, b) {
  return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]];
}

export class SignalClient {
  // `prefix`: the one the scene's names carry, when it is not the manifest's own.
  constructor(mujoco, model, data, manifest, {prefix} = {}) {
    this.mj = mujoco;
    this.m = model;
    this.d = data;
    this.manifest = manifest;
    this.warnings = [];
    if (!(manifest.format_version >= 1) || manifest.format_version > KNOWN_FORMAT_VERSION) {
      throw new ClientError(`manifest format_version ${manifest.format_version}: this client reads ` +
                            `1 to ${KNOWN_FORMAT_VERSION}`);
    }
    const step = model.opt.timestep;
    if (manifest.timestep && manifest.timestep_dependent !== false &&
        Math.abs(step - manifest.timestep) > 1e-9 * manifest.timestep) {
      this.warnings.push(`the scene steps at ${step} s but the model was emitted for ${manifest.timestep} s; ` +
                         `its ${(manifest.timestep_choices || []).join(', ')} follow the time step it was ` +
                         `emitted for`);
    }
    for (const law of manifest.laws) {
      this.warnings.push(`${law.kind} \`${law.path}\`: the runtime computes it each step; this client runs the ` +
                         `MJCF's static stand-in (actuators ${law.actuators.join(', ')})`);
    }
    this.rename = (name) => prefix === undefined ? name : prefix + name.slice(manifest.prefix.length);
    this.byPath = new Map();
    for (const s of manifest.signals) this.byPath.set(`${s.direction}:${s.path}`, s);
    this.kinematic = new Map();  // mocap index -> {linear, angular}
    this.engagements = new Map();  // tendon id -> {engaged, fraction, capacity, engage, disengage}
    this.switches = new Map();  // "object:id" -> {enabled, low, high}
    for (const s of manifest.signals) {
      if (s.direction !== 'input') continue;
      if (s.quantity === 'kinematic_linear_velocity' || s.quantity === 'kinematic_angular_velocity') {
        const k = this.m.body_mocapid[this.id(s)];
        const motion = this.kinematic.get(k) || {linear: [0, 0, 0], angular: [0, 0, 0]};
        motion[s.quantity === 'kinematic_linear_velocity' ? 'linear' : 'angular'] = s.initial_vector.map(num);
        this.kinematic.set(k, motion);
      } else if (s.quantity === 'engaged' && s.initial_vector.length === 1) {
        const on = s.initial !== 0;
        this.engagements.set(this.id(s), {engaged: on, fraction: on ? 1 : 0, capacity: num(s.initial_vector[0]),
                                          engage: num(s.low), disengage: num(s.high)});
      } else if (s.quantity === 'interaction_enabled') {
        this.switches.set(`${s.object}:${this.id(s)}`, {enabled: s.initial !== 0, low: num(s.low), high: num(s.high)});
      }
    }
  }

  id(s, k = 0) {
    const type = this.mj.mjtObj[OBJECT_TYPES[s.object]].value;
    const id = this.mj.mj_name2id(this.m, type, this.rename(s.names[k]));
    if (id < 0) throw new ClientError(`\`${s.path}\`: the model has no ${s.object} named ${this.rename(s.names[k])}`);
    return id;
  }

  find(path, direction) {
    let s = this.byPath.get(`${direction}:${path}`);
    const root = this.manifest.model + '.';
    if (!s && path.startsWith(root)) s = this.byPath.get(`${direction}:${path.slice(root.length)}`);
    if (!s) throw new ClientError(`no ${direction} named \`${path}\``);
    return s;
  }

  // Whether the client applies `s` as OpenPLX means it; else why not.
  exactness(s) {
    if (s.quantity === 'none') return `not mapped: ${s.reason}`;
    if (s.runtime) return 'needs the runtime each step (a law it computes); the MJCF\'s static stand-in runs instead';
    if (COMPOSED.has(s.quantity)) {
      for (const part of s.names) {
        const why = this.exactness(this.find(part, s.direction));
        if (why) return `its part \`${part}\` ${why}`;
      }
    }
    return '';
  }

  input(path) {
    const s = this.find(path, 'input');
    const why = this.exactness(s);
    if (s.quantity === 'none') throw new ClientError(`input \`${path}\` ${why}`);
    if (why) this.warnings.push(`input \`${path}\` ${why}`);
    return {binding: s, exact: !why, set: (value) => this.write(s, value)};
  }

  output(path) {
    const s = this.find(path, 'output');
    const why = this.exactness(s);
    if (s.quantity === 'none') throw new ClientError(`output \`${path}\` ${why}`);
    if (why) this.warnings.push(`output \`${path}\` ${why}`);
    return {binding: s, exact: !why, read: () => this.read(s)};
  }

  active() {  // MuJoCo 3.x keeps equalities' active flags in mjData, 2.2.2 in mjModel
    return ('eq_active' in this.d ? this.d.eq_active : this.m.eq_active);
  }

  reanchor(e, ratio) {
    const n = this.mj.mjNEQDATA, m = this.m, q = this.d.qpos;
    const a1 = m.jnt_qposadr[m.eq_obj1id[e]], a2 = m.jnt_qposadr[m.eq_obj2id[e]];
    const data = m.eq_data;
    data[e * n + 1] = 1 / ratio;
    data[e * n] = (q[a1] - m.qpos0[a1]) - data[e * n + 1] * (q[a2] - m.qpos0[a2]);
  }

  applySwitch(s, id) {
    const sw = this.switches.get(`${s.object}:${id}`);
    const m = this.m;
    if (s.object === 'actuator') {
      m.actuator_gear[6 * id] = sw.enabled ? 1 : 0;
      m.actuator_forcelimited[id] = 1;
      m.actuator_forcerange[2 * id] = sw.low;
      m.actuator_forcerange[2 * id + 1] = sw.high;
    } else if (s.object === 'joint') {
      m.jnt_limited[id] = sw.enabled ? 1 : 0;
      m.jnt_range[2 * id] = sw.low;
      m.jnt_range[2 * id + 1] = sw.high;
    } else {
      this.motorBand(s, id, sw.enabled ? sw.low : 0, sw.enabled ? sw.high : 0);
    }
  }

  motorBand(s, id, low, high) {
    const bias = this.mj.mj_name2id(this.m, this.mj.mjtObj.mjOBJ_ACTUATOR.value, this.rename(s.names[0]) + '/bias');
    if (bias < 0 && low + high !== 0) throw new ClientError(`\`${s.path}\`: the range must stay centred on 0`);
    this.m.tendon_frictionloss[id] = (high - low) / 2;
    if (bias >= 0) this.m.actuator_biasprm[bias * this.mj.mjNBIAS] = (high + low) / 2;
  }

  write(s, value) {
    const m = this.m, d = this.d, q = s.quantity;
    if (q === 'broadcast') return s.names.forEach((p) => this.write(this.find(p, 'input'), value));
    if (q === 'affine') return this.write(this.find(s.names[0], 'input'), num(s.low) * value + num(s.high));
    if (q === 'composite') return s.names.forEach((p, k) => this.write(this.find(p, 'input'), value[k]));
    const id = this.id(s);
    switch (q) {
      case 'ctrl': {
        const v = m.actuator_ctrllimited[id] ?
          Math.min(m.actuator_ctrlrange[2 * id + 1], Math.max(m.actuator_ctrlrange[2 * id], value)) : value;
        d.ctrl[id] = v;
        return;
      }
      case 'force_range':
        m.actuator_forcelimited[id] = 1;
        m.actuator_forcerange[2 * id] = value[0];
        m.actuator_forcerange[2 * id + 1] = value[1];
        return;
      case 'motor_force_range':
        return this.motorBand(s, id, value[0], value[1]);
      case 'interaction_enabled':
        this.switches.get(`${s.object}:${id}`).enabled = !!value;
        return this.applySwitch(s, id);
      case 'equality_active':
        for (let k = 0; k < s.names.length; ++k) this.active()[this.id(s, k)] = value ? 1 : 0;
        return;
      case 'engagement_fraction':
        m.tendon_frictionloss[id] = num(s.high) * Math.min(1, Math.max(0, value));
        return;
      case 'engaged':
        this.engagements.get(id).engaged = !!value;
        return;
      case 'engage_duration':
      case 'disengage_duration':
        this.engagements.get(id)[q === 'engage_duration' ? 'engage' : 'disengage'] = value;
        return;
      case 'gear_ratio':
        return this.reanchor(id, value);
      case 'gear_select': {
        const all = s.initial_vector.map(num), forward = all.slice(0, num(s.low)), reverse = all.slice(num(s.low));
        let ratio;
        if (value > 0 && value <= forward.length) ratio = Math.abs(forward[value - 1]);
        else if (value < 0 && -value <= reverse.length) ratio = -Math.abs(reverse[-value - 1]);
        else if (value === 0) ratio = num(s.high) !== 0 || forward.length === 0 ? 0 : Math.abs(forward[0]);
        else throw new ClientError(`\`${s.path}\`: no gear ${value}`);
        this.gears = {...this.gears, [id]: value};
        this.active()[id] = ratio !== 0 ? 1 : 0;
        if (ratio !== 0) this.reanchor(id, ratio);
        return;
      }
      case 'distance_target':
        m.eq_data[id * this.mj.mjNEQDATA] = value - m.tendon_length0[m.eq_obj1id[id]];
        return;
      case 'equality_target': {
        const c = s.initial_vector.map(num), low = num(s.low), high = num(s.high);
        const v = low < high || (low === high && c.length) ? Math.min(high, Math.max(low, value)) : value;
        m.eq_data[id * this.mj.mjNEQDATA] = (c.length ? poly(c, v) : v) - m.qpos0[m.jnt_qposadr[m.eq_obj1id[id]]];
        return;
      }
      case 'kinematic_linear_velocity':
      case 'kinematic_angular_velocity':
        this.kinematic.get(m.body_mocapid[id])[q === 'kinematic_linear_velocity' ? 'linear' : 'angular'] = [...value];
        return;
      case 'free_linear_velocity':
        for (let i = 0; i < 3; ++i) d.qvel[m.jnt_dofadr[id] + i] = value[i];
        return;
      case 'free_angular_velocity': {
        const b = m.jnt_bodyid[id], r = quatToMat(Array.from(d.xquat.slice(4 * b, 4 * b + 4)));
        for (let i = 0; i < 3; ++i) d.qvel[m.jnt_dofadr[id] + 3 + i] = r[i] * value[0] + r[3 + i] * value[1] + r[6 + i] * value[2];
        return;
      }
      default:
        throw new ClientError(`input \`${s.path}\`: this client does not apply ${q}`);
    }
  }

  vec(array, at) {
    return [array[at], array[at + 1], array[at + 2]];
  }

  // A point of body b's world velocity (cvel's linear part is at the root's subtree centre of mass).
  pointVelocity(b, point) {
    const w = this.vec(this.d.cvel, 6 * b), v = this.vec(this.d.cvel, 6 * b + 3);
    const c = this.vec(this.d.subtree_com, 3 * this.m.body_rootid[b]);
    const arm = cross(w, [point[0] - c[0], point[1] - c[1], point[2] - c[2]]);
    return [v[0] + arm[0], v[1] + arm[1], v[2] + arm[2]];
  }

  read(s) {
    const m = this.m, d = this.d, q = s.quantity;
    if (q === 'constant') return num(s.initial);
    if (q === 'affine') return num(s.low) * this.read(this.find(s.names[0], 'output')) + num(s.high);
    if (q === 'composite') return s.names.flatMap((p) => [this.read(this.find(p, 'output'))].flat());
    const id = this.id(s), n = this.mj.mjNEQDATA;
    switch (q) {
      case 'ctrl': return d.ctrl[id];
      case 'joint_position': {
        const qpos = d.qpos[m.jnt_qposadr[id]];
        return num(s.sign) * (s.initial_vector.length ? polyInverse(s.initial_vector.map(num), qpos, num(s.low), num(s.high)) : qpos);
      }
      case 'joint_velocity': return num(s.sign) * d.qvel[m.jnt_dofadr[id]];
      case 'actuator_force': return d.actuator_force[id] * m.actuator_gear[6 * id];
      case 'equality_active': return this.active()[id] ? 1 : 0;
      case 'interaction_enabled': return this.switches.get(`${s.object}:${id}`).enabled ? 1 : 0;
      case 'engagement_fraction': return num(s.high) > 0 ? m.tendon_frictionloss[id] / num(s.high) : 0;
      case 'engaged': return this.engagements.get(id).engaged ? 1 : 0;
      case 'gear_ratio': return this.active()[id] ? 1 / m.eq_data[id * n + 1] : 0;
      case 'gear_select': return (this.gears || {})[id] ?? num(s.initial);
      case 'distance_target': return m.eq_data[id * n] + m.tendon_length0[m.eq_obj1id[id]];
      case 'equality_target': {
        const held = m.eq_data[id * n] + m.qpos0[m.jnt_qposadr[m.eq_obj1id[id]]];
        return polyInverse(s.initial_vector.map(num), held, num(s.low), num(s.high));
      }
      case 'tendon_length': return d.ten_length[id];
      case 'tendon_velocity': return d.ten_velocity[id];
      case 'joint_limit_force': case 'equality_force': case 'tendon_limit_force': case 'motor_force': {
        const type = this.mj.mjtConstraint[CONSTRAINT_ROWS[q]].value;
        let total = 0;
        for (let r = 0; r < d.nefc; ++r) if (d.efc_type[r] === type && d.efc_id[r] === id) total += d.efc_force[r];
        if (q === 'motor_force') {
          const bias = this.mj.mj_name2id(m, this.mj.mjtObj.mjOBJ_ACTUATOR.value, this.rename(s.names[0]) + '/bias');
          if (bias >= 0) total += d.actuator_force[bias];
        }
        return total;
      }
      case 'sensor_fields':
        return s.names.map((_, k) => d.sensordata[m.sensor_adr[this.id({...s, object: 'sensor'}, k)] + num(s.initial_vector[k])]);
      case 'body_position': return this.vec(d.xpos, 3 * id);
      case 'body_rpy': return rpy(quatToMat(Array.from(d.xquat.slice(4 * id, 4 * id + 4))));
      case 'body_linear_velocity': return this.pointVelocity(id, this.vec(d.xpos, 3 * id));
      case 'body_angular_velocity': return this.vec(d.cvel, 6 * id);
      case 'site_position': return this.vec(d.site_xpos, 3 * id);
      case 'site_rpy': return rpy(Array.from(d.site_xmat.slice(9 * id, 9 * id + 9)));
      case 'site_linear_velocity': return this.pointVelocity(m.site_bodyid[id], this.vec(d.site_xpos, 3 * id));
      case 'site_angular_velocity': return this.vec(d.cvel, 6 * m.site_bodyid[id]);
      default:
        throw new ClientError(`output \`${s.path}\`: this client does not read ${q}`);
    }
  }

  // The per-step work after each mj_step: kinematic bodies move at their velocities, automatic clutches ramp.
  afterStep() {
    const h = this.m.opt.timestep, d = this.d;
    for (const [k, {linear, angular}] of this.kinematic) {
      for (let i = 0; i < 3; ++i) d.mocap_pos[3 * k + i] += h * linear[i];
      const speed = Math.hypot(...angular);
      if (speed > 0) {  // turn by |w| h about w (world axes): q <- dq q
        const half = speed * h / 2, s = Math.sin(half) / speed;
        const [a, b, c, e] = [Math.cos(half), angular[0] * s, angular[1] * s, angular[2] * s];
        const [w, x, y, z] = Array.from(d.mocap_quat.slice(4 * k, 4 * k + 4));
        const turned = [a * w - b * x - c * y - e * z, a * x + b * w + c * z - e * y,
                        a * y - b * z + c * w + e * x, a * z + b * y - c * x + e * w];
        const norm = Math.hypot(...turned);
        for (let i = 0; i < 4; ++i) d.mocap_quat[4 * k + i] = turned[i] / norm;
      }
    }
    for (const [tendon, e] of this.engagements) {
      const target = e.engaged ? 1 : 0, time = e.engaged ? e.engage : e.disengage;
      const change = time > 0 ? h / time : 1;
      e.fraction = target > e.fraction ? Math.min(target, e.fraction + change) : Math.max(target, e.fraction - change);
      this.m.tendon_frictionloss[tendon] = e.capacity * e.fraction;
    }
  }
}
