#include "encoder/src/dataset/colmap_text.h"

#include <cmath>
#include <cstdint>
#include <sstream>

namespace m4d {
namespace {

// Splits text into lines ('\n' or "\r\n"), numbering them from 1 for messages.
class LineReader {
 public:
  explicit LineReader(const std::string& text) : text_(text) {}

  bool Next(std::string* line) {
    if (pos_ >= text_.size()) return false;
    size_t end = text_.find('\n', pos_);
    if (end == std::string::npos) end = text_.size();
    *line = text_.substr(pos_, end - pos_);
    if (!line->empty() && line->back() == '\r') line->pop_back();
    pos_ = end + 1;
    ++number_;
    return true;
  }
  // The next line that is neither blank nor a comment.
  bool NextRecord(std::string* line) {
    while (Next(line)) {
      const size_t first = line->find_first_not_of(" \t");
      if (first != std::string::npos && (*line)[first] != '#') return true;
    }
    return false;
  }
  int number() const { return number_; }

 private:
  const std::string& text_;
  size_t pos_ = 0;
  int number_ = 0;
};

Status BadLine(const char* file, const LineReader& lines) {
  return BitstreamError(std::string("colmap: ") + file + " line " + std::to_string(lines.number()) +
                        " does not parse");
}

// A finite value within float range, as the values end up in floats.
bool ReadDouble(std::istringstream& words, double* v) {
  return static_cast<bool>(words >> *v) && std::fabs(*v) <= 1e30;
}

bool ReadId(std::istringstream& words, uint32_t* id) {
  int64_t value;
  if (!(words >> value) || value < 0 || value > UINT32_MAX) return false;
  *id = static_cast<uint32_t>(value);
  return true;
}

}  // namespace

Status ParseColmapCamerasText(const std::string& text, std::vector<ColmapCamera>* cameras) {
  cameras->clear();
  LineReader lines(text);
  std::string line;
  while (lines.NextRecord(&line)) {
    std::istringstream words(line);
    ColmapCamera camera;
    std::string model;
    int64_t width, height;
    if (!ReadId(words, &camera.id) || !(words >> model >> width >> height) || width < 0 ||
        height < 0) {
      return BadLine("cameras.txt", lines);
    }
    camera.model_id = ColmapModelId(model);
    if (camera.model_id < 0) return BitstreamError("colmap: unknown camera model " + model);
    camera.width = static_cast<uint64_t>(width);
    camera.height = static_cast<uint64_t>(height);
    camera.params.resize(ColmapModelParamCount(camera.model_id));
    for (double& param : camera.params) {
      if (!ReadDouble(words, &param)) return BadLine("cameras.txt", lines);
    }
    std::string extra;
    if (words >> extra) return BadLine("cameras.txt", lines);
    cameras->push_back(camera);
  }
  return Status::Ok();
}

Status ParseColmapImagesText(const std::string& text, std::vector<ColmapImage>* images) {
  images->clear();
  LineReader lines(text);
  std::string line;
  while (lines.NextRecord(&line)) {
    std::istringstream words(line);
    ColmapImage image;
    bool ok = ReadId(words, &image.id);
    for (double& q : image.qvec) ok = ok && ReadDouble(words, &q);
    for (double& t : image.tvec) ok = ok && ReadDouble(words, &t);
    ok = ok && ReadId(words, &image.camera_id);
    // The name is the rest of the line, so names with spaces survive.
    if (ok) std::getline(words >> std::ws, image.name);
    image.name.erase(image.name.find_last_not_of(" \t") + 1);
    if (!ok || image.name.empty()) return BadLine("images.txt", lines);
    images->push_back(image);
    lines.Next(&line);  // the image's 2D points, unused (may be empty or missing at the end)
  }
  return Status::Ok();
}

Status ParseColmapPointsText(const std::string& text, PointCloud* points) {
  points->positions.clear();
  points->colors.clear();
  LineReader lines(text);
  std::string line;
  while (lines.NextRecord(&line)) {
    std::istringstream words(line);
    uint64_t id;
    double xyz[3];
    int rgb[3];
    bool ok = static_cast<bool>(words >> id);
    for (double& v : xyz) ok = ok && ReadDouble(words, &v);
    for (int& c : rgb) ok = ok && (words >> c) && c >= 0 && c <= 255;
    if (!ok) return BadLine("points3D.txt", lines);
    for (int a = 0; a < 3; ++a) {
      points->positions.push_back(static_cast<float>(xyz[a]));
      points->colors.push_back(static_cast<float>(rgb[a]) / 255.0f);
    }
  }
  return Status::Ok();
}

}  // namespace m4d
