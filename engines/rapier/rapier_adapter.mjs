#!/usr/bin/env node
// Rapier 2-D (the deterministic WebAssembly build of its official JavaScript bindings) as a
// rockbench external engine (protocol 1; the protocol's definition is InputJson and ReadPoses in
// engines/external/protocol.cc).
//
//     node rapier_adapter.mjs INPUT.json
//
// One kinematic-velocity-based ground cuboid (at rest under the inertial drive) whose top is
// y = 0 at t = 0, one dynamic cuboid per block with the input's mass and inertia, stepped
// `steps` times at the input's step; the poses go to the input's poses_file. Each contact pair
// of the input gets a collider of its own on each of its two bodies, and only the two colliders
// of one pair meet (a contact filter hook; collision groups with contact_recycling), so that every
// pair has exactly its friction coefficient (Min rule, the same value on both sides). Rapier
// computes in f32: the poses are f32 values written as the doubles they are.
import { closeSync, openSync, readFileSync, writeSync } from "node:fs";
import RAPIER from "@dimforge/rapier2d-deterministic-compat";

function fail(msg) {
  process.stderr.write(`rapier_adapter.mjs: ${msg}\n`);
  process.exit(1);
}

function finiteOr(v, fallback) {
  return typeof v === "number" && Number.isFinite(v) ? v : fallback;
}

// The [rapier] table's defaults, read from its one place, manifest.toml beside this file:
// rockbench sends every key (the table it resolved against the manifest), and a hand-written
// input that leaves a key out gets the manifest's default here. Reads the `default = ` line of
// each [settings.KEY] table (a number or a flag: what the manifest's keys are).
function manifestDefaults() {
  const text = readFileSync(new URL("manifest.toml", import.meta.url), "utf8");
  const defaults = {};
  let key = null;
  for (const line of text.split("\n")) {
    const table = line.match(/^\[settings\.([A-Za-z0-9_]+)\]\s*$/);
    if (table) {
      key = table[1];
      continue;
    }
    if (line.startsWith("[")) key = null;
    const value = line.match(/^default\s*=\s*(\S+)\s*$/);
    if (key !== null && value) {
      const v = value[1];
      defaults[key] = v === "true" ? true : v === "false" ? false : Number(v);
      if (typeof defaults[key] === "number" && !Number.isFinite(defaults[key])) {
        fail(`manifest.toml: settings.${key}.default is not a number or a flag: ${v}`);
      }
    }
  }
  return defaults;
}

async function main(argv) {
  if (argv.length !== 1) fail("usage: node rapier_adapter.mjs INPUT.json");
  const run = JSON.parse(readFileSync(argv[0], "utf8"));
  if (run.protocol_version !== 1) {
    fail(`speaks protocol 1, the input is ${run.protocol_version}`);
  }
  if (run.dimensions !== 2) fail(`simulates 2 dimensions, the input has ${run.dimensions}`);
  const s = { ...manifestDefaults(), ...(run.settings || {}) };
  const dt = run.time_step_s;
  const steps = run.steps;
  const every = run.output_every_steps;
  const g = run.gravity_mps2;
  const blocks = run.blocks;
  const drive = run.drive;
  const kinematic = drive.kind === "kinematic";
  if (!kinematic && drive.kind !== "inertial") fail(`unknown drive '${drive.kind}'`);

  await RAPIER.init();
  const world = new RAPIER.World({ x: 0.0, y: -g });
  world.timestep = dt;
  world.lengthUnit = 1.0; // the normalized lengths below are then in m
  world.numSolverIterations = s.num_solver_iterations;
  world.numInternalPgsIterations = s.num_internal_pgs_iterations;
  const ip = world.integrationParameters;
  ip.normalizedAllowedLinearError = s.allowed_linear_error;
  ip.normalizedPredictionDistance = s.prediction_distance;
  ip.raw.contact_natural_frequency = s.contact_natural_frequency;

  // The ground: a cuboid far wider than the stack, 2 m thick (its top is then exactly 0 in f32).
  let size = 0.5;
  for (const b of blocks) size = Math.max(size, 0.5 * b.width_m, 0.5 * b.height_m);
  const groundHalfW = 40.0 * size;
  const groundHalfH = 1.0;
  const ux0 = kinematic ? drive.ux_m[0] : 0.0;
  const uy0 = kinematic ? drive.uy_m[0] : 0.0;
  const gvx = kinematic ? drive.ux0_mps : 0.0;
  const gvy = kinematic ? drive.uy0_mps : 0.0;
  // Rapier's positions are f32: the world's origin sits at the stack's mass centre at t = 0
  // (rounded to 2^-10 m, so that the ground's top stays exact), where their ulp is smallest.
  let mass = 0.0, mx = 0.0, my = 0.0;
  for (const b of blocks) {
    mass += b.mass_kg;
    mx += b.mass_kg * b.x_m;
    my += b.mass_kg * b.y_m;
  }
  const ox = Math.round((mx / mass) * 1024) / 1024;
  const oy = Math.round((my / mass) * 1024) / 1024;
  // Always a kinematic body (at rest under the inertial drive): Rapier 0.35 gives a contact with
  // a FIXED body its own softness (static_contact_softness, 60 Hz, not settable from JavaScript),
  // so contact_natural_frequency would not reach the ground contact.
  const ground = world.createRigidBody(
    RAPIER.RigidBodyDesc.kinematicVelocityBased()
      .setTranslation(ux0 - ox, uy0 - oy - groundHalfH)
      .setLinvel(gvx, gvy)
      .setCanSleep(false),
  );

  // The blocks, bottom first, placed as the input has them (relative to the ground at t = 0).
  const bodies = [ground];
  for (const b of blocks) {
    const body = world.createRigidBody(
      RAPIER.RigidBodyDesc.dynamic()
        .setTranslation(b.x_m + ux0 - ox, b.y_m + uy0 - oy)
        .setRotation(b.angle_rad)
        .setLinvel(b.vx_mps + gvx, b.vy_mps + gvy)
        .setAngvel(b.omega_radps)
        .setAdditionalMassProperties(b.mass_kg, { x: 0.0, y: 0.0 }, b.inertia_kgm2)
        .setCanSleep(false)
        .setCcdEnabled(false),
    );
    bodies.push(body);
  }

  // One collider per (pair, side): only the pair's two colliders meet.
  const pairs = run.contact_pairs;
  // Rapier 0.35 "recycles" a pair's contacts (keeps its points, distances and solver anchors)
  // while its relative pose moved less than 0.05 m, a setting the JavaScript bindings do not
  // expose; a pair with an active hook is never recycled. So: the hook unless contact_recycling.
  const useGroups = pairs.length <= 16 && s.contact_recycling;
  const allowed = new Set(); // "h1,h2" of collider handles that may touch (the hook's filter)
  const halfExtents = (body) =>
    body === 0
      ? [groundHalfW, groundHalfH]
      : [0.5 * blocks[body - 1].width_m, 0.5 * blocks[body - 1].height_m];
  for (const [p, pair] of pairs.entries()) {
    const mu = finiteOr(pair.friction, s.friction);
    const handles = [];
    for (const body of [pair.lower, pair.upper]) {
      if (!(body >= 0 && body <= blocks.length)) fail(`contact pair ${p}: no body ${body}`);
      const [hx, hy] = halfExtents(body);
      let desc = RAPIER.ColliderDesc.cuboid(hx, hy)
        .setDensity(0.0)
        .setFriction(mu)
        .setFrictionCombineRule(RAPIER.CoefficientCombineRule.Min)
        .setRestitution(0.0)
        .setRestitutionCombineRule(RAPIER.CoefficientCombineRule.Min)
        .setContactSkin(s.contact_skin);
      if (useGroups) {
        const bit = 1 << p;
        desc = desc.setCollisionGroups(((bit << 16) | bit) >>> 0);
      } else {
        desc = desc.setActiveHooks(RAPIER.ActiveHooks.FILTER_CONTACT_PAIRS);
      }
      handles.push(world.createCollider(desc, bodies[body]).handle);
    }
    allowed.add(`${handles[0]},${handles[1]}`);
    allowed.add(`${handles[1]},${handles[0]}`);
  }
  const hooks = useGroups
    ? undefined
    : {
        filterContactPair: (c1, c2) =>
          allowed.has(`${c1},${c2}`) ? RAPIER.SolverFlags.COMPUTE_IMPULSE : null,
        filterIntersectionPair: () => false,
      };

  // The mass properties are the input's (f32).
  for (const [k, b] of blocks.entries()) {
    const body = bodies[k + 1];
    body.recomputeMassPropertiesFromColliders();
    const rel = (a, e) => Math.abs(a - e) / Math.abs(e);
    if (rel(body.mass(), b.mass_kg) > 1e-6 || rel(body.principalInertia(), b.inertia_kgm2) > 1e-6) {
      fail(
        `block ${k + 1}: Rapier has mass ${body.mass()} kg and inertia ` +
          `${body.principalInertia()} kg m^2, the input ${b.mass_kg} and ${b.inertia_kgm2}`,
      );
    }
  }

  // The poses file: t = 0, every `every`-th step, the last step.
  const fd = openSync(run.poses_file, "w");
  let buf = [];
  const flush = () => {
    if (buf.length) writeSync(fd, buf.join(""));
    buf = [];
  };
  const header = ["t_s"];
  for (let k = 1; k <= blocks.length; ++k) {
    header.push(`x${k}_m`, `y${k}_m`, `angle${k}_rad`, `vx${k}_mps`, `vy${k}_mps`, `omega${k}_radps`);
  }
  buf.push(`# Rapier ${RAPIER.version()} (@dimforge/rapier2d-deterministic-compat, f32)\n`);
  buf.push(header.join(",") + "\n");
  const row = (n) => {
    const f = [String(n * dt)];
    for (let k = 1; k < bodies.length; ++k) {
      const b = bodies[k];
      const x = b.translation();
      const v = b.linvel();
      f.push(String(x.x + ox + sx), String(x.y + oy + sy), String(b.rotation()), String(v.x), String(v.y), String(b.angvel()));
    }
    buf.push(f.join(",") + "\n");
    if (buf.length >= 4096) flush();
  };

  let sx = 0.0, sy = 0.0;
  const g0 = { x: ux0 - ox, y: uy0 - oy - groundHalfH };
  row(0);
  const ax = kinematic ? [] : drive.ax_mps2;
  const ay = kinematic ? [] : drive.ay_mps2;
  const gravity = { x: 0.0, y: -g };
  for (let n = 0; n < steps; ++n) {
    if (kinematic) {
      // The ground moves with (u_{n+1} - u_n) / dt during step n, from a frame that follows it
      // (below): an f32 position 2 m away rounds a 5e-5 m step's increment by up to 1.2e-7 m.
      ground.setLinvel(
        { x: (drive.ux_m[n + 1] - drive.ux_m[n]) / dt, y: (drive.uy_m[n + 1] - drive.uy_m[n]) / dt },
        false,
      );
    } else {
      // The base's acceleration as the effective gravity of the base frame.
      gravity.x = ax.length ? -ax[n] : 0.0;
      gravity.y = -(g + (ay.length ? ay[n] : 0.0));
      // Rapier holds gravity in f32: a base acceleration beyond its range (3.4e38 m/s^2) cannot
      // be given to it (it would step as if the base were still). The state after this step is
      // not finite in Rapier's arithmetic: one row of NaN ends the run there (status non_finite).
      if (!Number.isFinite(Math.fround(gravity.x)) || !Number.isFinite(Math.fround(gravity.y))) {
        const f = [String((n + 1) * dt)];
        for (let k = 1; k < bodies.length; ++k) f.push("NaN", "NaN", "NaN", "NaN", "NaN", "NaN");
        buf.push(f.join(",") + "\n");
        break;
      }
      world.gravity = gravity;
    }
    world.step(undefined, hooks);
    if (kinematic) {
      // Shift the world back by the ground's displacement (positions only, a Galilean change of
      // frame): the ground stays at g0, the blocks near the origin; the poses add u_{n+1} - u_0.
      const gp = ground.translation();
      const dx = gp.x - g0.x, dy = gp.y - g0.y;
      ground.setTranslation(g0, false);
      for (let k = 1; k < bodies.length; ++k) {
        const p = bodies[k].translation();
        bodies[k].setTranslation({ x: p.x - dx, y: p.y - dy }, false);
      }
      sx = drive.ux_m[n + 1] - ux0;
      sy = drive.uy_m[n + 1] - uy0;
    }
    if ((n + 1) % every === 0 || n + 1 === steps) row(n + 1);
  }
  flush();
  closeSync(fd);
  world.free();
}

main(process.argv.slice(2)).catch((e) => fail(e && e.stack ? e.stack : String(e)));
