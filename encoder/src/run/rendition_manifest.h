// The rendition manifest of `m4d encode --renditions` (the role of a DASH MPD): per rendition
// its stream's name, rate point, bandwidth and GOP index, for players that switch rendition
// at random-access GOP boundaries.
#ifndef M4D_ENCODER_RUN_RENDITION_MANIFEST_H_
#define M4D_ENCODER_RUN_RENDITION_MANIFEST_H_

#include <cstdint>
#include <string>
#include <vector>

#include "sdk/src/common/status.h"

namespace m4d {

// OUT.m4d -> OUT (a name without the .m4d extension stays whole).
std::string RenditionBase(const std::string& output);
// OUT.m4d, "r1" -> OUT.r1.m4d.
std::string RenditionPath(const std::string& output, const std::string& id);
// OUT.m4d -> OUT.manifest.json.
std::string ManifestPath(const std::string& output);

struct RenditionStream {
  std::string id;          // e.g. "r1"
  std::string rate_point;  // the rate point it was coded at
  std::string url;         // its stream's name, relative to the manifest
  const std::vector<uint8_t>* stream = nullptr;
};

// The manifest's JSON text: {"format": "m4d-manifest", "version": 1, "frames", "fps",
// "renditions": [{"id", "url", "rate_point", "bandwidth" (bits per second over the whole
// stream), "bytes", "gops"}] sorted by bandwidth, ascending}. An error when a stream is
// damaged or the renditions' frames, frame rates or GOPs (first frame, frames,
// random_access) differ.
Status RenditionManifestJson(const std::vector<RenditionStream>& renditions, std::string* json);

}  // namespace m4d

#endif  // M4D_ENCODER_RUN_RENDITION_MANIFEST_H_
