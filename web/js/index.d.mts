// Type declarations of index.mjs, the entry point of the m4d-player package.
export * from './m4d.mjs';
export * from './worker_decoder.mjs';
export * from './player_core.mjs';
export * from './splat_frame.mjs';
