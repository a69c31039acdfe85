// Tests of the npm package m4d-player (scripts/pack_web.sh, web/package/package.json): the
// tarball npm packs holds every file its exports name, its version is the SDK's, and the
// packed modules decode a stream in Node.js. Needs scripts/build_web.sh.
import assert from 'node:assert/strict';
import { execFileSync } from 'node:child_process';
import { existsSync, mkdtempSync, readFileSync, rmSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { dirname, join } from 'node:path';
import { test } from 'node:test';
import { fileURLToPath, pathToFileURL } from 'node:url';

const root = fileURLToPath(new URL('../../', import.meta.url));

test('pack_web.sh packs a package whose exports resolve to files in the tarball', async (t) => {
  const dir = mkdtempSync(join(tmpdir(), 'm4d-pack-'));
  try {
    const tarball = execFileSync(join(root, 'scripts/pack_web.sh'), ['--out', dir], { stdio: ['ignore', 'pipe', 'pipe'] })
      .toString().trim();
    assert.equal(tarball, join(dir, 'm4d-player-0.9.0.tgz'));
    const files = new Set(execFileSync('tar', ['-tzf', tarball]).toString().split('\n').filter(Boolean));
    const pkg = JSON.parse(execFileSync('tar', ['-xzOf', tarball, 'package/package.json']).toString());
    const header = readFileSync(join(root, 'sdk/include/m4d/m4d.h'), 'utf8');
    const part = (name) => header.match(new RegExp(`#define M4D_VERSION_${name} (\\d+)`))[1];
    assert.equal(pkg.name, 'm4d-player');
    assert.equal(pkg.version, `${part('MAJOR')}.${part('MINOR')}.${part('PATCH')}`);
    assert.equal(pkg.type, 'module');
    for (const entry of ['.', './decoder', './worker', './worker-script', './wasm', './player-core', './splat-frame',
      './spark', './playcanvas', './gop-streamer']) {
      assert.ok(pkg.exports[entry], `export ${entry}`);
    }
    for (const [entry, target] of Object.entries(pkg.exports)) {
      for (const file of typeof target === 'string' ? [target] : Object.values(target)) {
        assert.ok(files.has(`package/${file.replace(/^\.\//, '')}`), `${entry}: ${file} is not in the tarball`);
      }
    }
    t.diagnostic(`${files.size} files, exports: ${Object.keys(pkg.exports).join(' ')}`);
    for (const name of Object.keys(pkg.peerDependencies)) assert.equal(pkg.peerDependenciesMeta[name].optional, true);
    // The packed modules work: decode the first frame of a stream through the package's entry.
    execFileSync('tar', ['-xzf', tarball, '-C', dir]);
    assert.ok(existsSync(join(dir, 'package/js/m4d_worker.mjs')));
    // Every relative import of a packed module names a packed file (the adapters take
    // SplatFrames from ../js/splat_frame.mjs); the adapters and the streamer load in Node.js.
    for (const file of [...files].filter((f) => f.endsWith('.mjs'))) {
      const text = readFileSync(join(dir, file), 'utf8');
      for (const [, target] of text.matchAll(/(?:from|import\()\s*'(\.\.?\/[^']+)'/g)) {
        assert.ok(files.has(join(dirname(file), target)), `${file} imports ${target}, not in the tarball`);
      }
    }
    const spark = await import(pathToFileURL(join(dir, 'package', pkg.exports['./spark'].default)).href);
    const playcanvas = await import(pathToFileURL(join(dir, 'package', pkg.exports['./playcanvas'].default)).href);
    const streamer = await import(pathToFileURL(join(dir, 'package', pkg.exports['./gop-streamer'].default)).href);
    assert.equal(typeof spark.M4dSparkAdapter, 'function');
    assert.equal(typeof playcanvas.M4dPlayCanvasAdapter, 'function');
    assert.equal(typeof streamer.GopStreamer, 'function');
    assert.equal(spark.splatFrameOfM4dFrame, undefined, 'SplatFrames are made by splat_frame.mjs only');
    assert.equal(playcanvas.splatFrameOf, undefined, 'SplatFrames are made by splat_frame.mjs only');
    const m4dPlayer = await import(pathToFileURL(join(dir, 'package/js/index.mjs')).href);
    const m4d = await m4dPlayer.loadM4d();
    assert.equal(m4d.version(), pkg.version);
    const decoder = m4d.openDecoder();
    decoder.push(readFileSync(join(root, 'conformance/streams/enc_adaptive_gop.m4d')));
    decoder.end();
    const frame = m4dPlayer.splatFrameFromDecoder(decoder.nextFrame(), { staticChanged: true });
    assert.equal(frame.frameIndex, 0);
    assert.ok(frame.static.count > 0 && frame.dynamic.count > 0);
    assert.equal(typeof m4dPlayer.M4dWorkerDecoder, 'function');
    assert.equal(typeof m4dPlayer.PlayerCore, 'function');
    decoder.close();
  } finally {
    rmSync(dir, { recursive: true, force: true });
  }
});

test('every export and member the package\'s TypeScript declarations declare exists', async () => {
  const instances = {
    M4dWorkerDecoder: (api) => new api.M4dWorkerDecoder(),
    PlayerCore: (api) => new api.PlayerCore({ nextFrame: async () => null, seek: async () => false }),
    SplatFrameMaker: (api) => new api.SplatFrameMaker(),
    DecoderFrameSource: (api) => new api.DecoderFrameSource({ nextFrame: () => null, seek: () => true }),
  };
  let checked = 0;
  for (const name of ['splat_frame', 'worker_decoder', 'player_core']) {
    const api = await import(new URL(`../js/${name}.mjs`, import.meta.url));
    const declarations = readFileSync(new URL(`../js/${name}.d.mts`, import.meta.url), 'utf8');
    for (const [, kind, symbol] of declarations.matchAll(/export declare (function|const|class) (\w+)/g)) {
      assert.notEqual(api[symbol], undefined, `${name}: ${kind} ${symbol} is declared but not exported`);
      ++checked;
    }
    for (const [, symbol, body] of declarations.matchAll(/export declare class (\w+)[^{]*\{([\s\S]*?)\n\}/g)) {
      const instance = instances[symbol](api);
      for (const [, member] of body.matchAll(/^  (?:readonly )?(\w+)[(:<]/gm)) {
        if (member === 'constructor') continue;
        assert.ok(member in instance, `${symbol}.${member} is declared but not defined`);
        ++checked;
      }
    }
  }
  assert.ok(checked > 30, `${checked} members`);
});
