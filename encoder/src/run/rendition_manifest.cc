#include "encoder/src/run/rendition_manifest.h"

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>

#include "encoder/src/stream/gop_index.h"

namespace m4d {

std::string RenditionBase(const std::string& output) {
  const std::string ext = ".m4d";
  if (output.size() > ext.size() &&
      output.compare(output.size() - ext.size(), ext.size(), ext) == 0) {
    return output.substr(0, output.size() - ext.size());
  }
  return output;
}

std::string RenditionPath(const std::string& output, const std::string& id) {
  return RenditionBase(output) + "." + id + ".m4d";
}

std::string ManifestPath(const std::string& output) {
  return RenditionBase(output) + ".manifest.json";
}

namespace {

bool SameGops(const GopIndex& a, const GopIndex& b) {
  if (a.gops.size() != b.gops.size()) return false;
  for (size_t g = 0; g < a.gops.size(); ++g) {
    const GopEntry &x = a.gops[g], &y = b.gops[g];
    if (x.frame != y.frame || x.frames != y.frames || x.random_access != y.random_access) {
      return false;
    }
  }
  return true;
}

}  // namespace

Status RenditionManifestJson(const std::vector<RenditionStream>& renditions, std::string* json) {
  if (renditions.empty()) return Status(M4D_ERR_INVALID_ARG, "manifest: no rendition");
  std::vector<GopIndex> indexes(renditions.size());
  for (size_t r = 0; r < renditions.size(); ++r) {
    const std::vector<uint8_t>& s = *renditions[r].stream;
    Status status = BuildGopIndex(s.data(), s.size(), &indexes[r]);
    if (!status.ok()) {
      return Status(status.code(), "rendition " + renditions[r].id + ": " + status.message());
    }
    if (indexes[r].frames < 1 || !(indexes[r].fps > 0)) {
      return Status(M4D_ERR_BITSTREAM, "rendition " + renditions[r].id + ": no frame");
    }
    if (r > 0 && (indexes[r].frames != indexes[0].frames || indexes[r].fps != indexes[0].fps ||
                  !SameGops(indexes[r], indexes[0]))) {
      return Status(M4D_ERR_INVALID_ARG, "rendition " + renditions[r].id +
                                             ": its frames or GOPs differ from rendition " +
                                             renditions[0].id + "'s");
    }
  }
  std::vector<nlohmann::json> entries;
  for (size_t r = 0; r < renditions.size(); ++r) {
    const GopIndex& index = indexes[r];
    const double seconds = static_cast<double>(index.frames) / index.fps;
    // The manifest's objects keep their keys sorted (nlohmann::json), as they always have.
    const nlohmann::json gops = GopsJson(index.gops);
    entries.push_back(
        {{"id", renditions[r].id},
         {"url", renditions[r].url},
         {"rate_point", renditions[r].rate_point},
         {"bandwidth", std::llround(8.0 * static_cast<double>(index.stream_bytes) / seconds)},
         {"bytes", index.stream_bytes},
         {"gops", gops}});
  }
  std::stable_sort(entries.begin(), entries.end(),
                   [](const nlohmann::json& a, const nlohmann::json& b) {
                     return a["bandwidth"].get<int64_t>() < b["bandwidth"].get<int64_t>();
                   });
  const nlohmann::json manifest = {{"format", "m4d-manifest"},
                                   {"version", 1},
                                   {"frames", indexes[0].frames},
                                   {"fps", indexes[0].fps},
                                   {"renditions", entries}};
  *json = manifest.dump(2) + "\n";
  return Status::Ok();
}

}  // namespace m4d
