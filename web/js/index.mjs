// index.mjs - the entry point of the m4d-player package: the WebAssembly decoder (m4d.mjs),
// the decoder in a Web Worker (worker_decoder.mjs), the player core (player_core.mjs) and the
// SplatFrame layouts (splat_frame.mjs). Adapters for viewers are separate entries.
export { errorCodeName, loadM4d } from './m4d.mjs';
export { M4dWorkerDecoder } from './worker_decoder.mjs';
export { PlayerCore } from './player_core.mjs';
export {
  DecoderFrameSource, SH_C0, SplatFrameMaker, copySplatLayer, layersEqual, linearScales, normalisedRotationsXyzw, opacities, rgbFromShDc,
  splatFrameFromDecoder, transferablesOf,
} from './splat_frame.mjs';
