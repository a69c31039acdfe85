// Renditions for the adaptive-bitrate tests (abr_controller.test.mjs, abr_viewer.test.mjs):
// a tiny generated scene encoded by `m4d encode --renditions r1,r5` (needs the native build,
// scripts/build.sh) into `dir` as abr.manifest.json, abr.r1.m4d and abr.r5.m4d: 16 frames at
// 5 fps in GOPs of 2 frames, each a random-access point. Returns the manifest (validated).
import { execFileSync } from 'node:child_process';
import { readFileSync } from 'node:fs';
import { join } from 'node:path';
import { fileURLToPath } from 'node:url';

import { validateManifest } from '../js/abr_controller.mjs';

const m4dCli = fileURLToPath(new URL('../../build/release/tools/m4d/m4d', import.meta.url));

// Encodes the renditions into `dir` (an existing directory); resolves to the manifest.
export function encodeRenditions(dir) {
  execFileSync(m4dCli, ['scene', '-o', join(dir, 'scene'), '--cameras', '5', '--width', '48',
    '--height', '36', '--frames', '16', '--points', '1500'], { stdio: 'ignore' });
  execFileSync(m4dCli, ['encode', join(dir, 'scene'), '-o', join(dir, 'abr.m4d'),
    '--keyframe-iterations', '60', '--retrain-iterations', '20', '--motion-iterations', '5',
    '--compensation-iterations', '5', '--lookahead', '1', '--max-gaussians', '3000',
    '--fixed-gop', '2', '--random-access', '0', '--fps', '5', '--renditions', 'r1,r5'],
  { stdio: 'ignore' });
  return validateManifest(JSON.parse(readFileSync(join(dir, 'abr.manifest.json'), 'utf8')));
}
