// SceneRenderer: draws the synthetic scene with OpenGL ES 3 in a headless context (Mesa's
// llvmpipe is enough). Meshes and mipmapped textures are uploaded once; each view is drawn
// at `supersample` times the output size with multisampling, read back and box-filtered
// down to 8-bit RGB, so that fine texture detail is smooth enough for a Gaussian model.
#ifndef M4D_ENCODER_SYNTHETIC_SCENE_RENDERER_H_
#define M4D_ENCODER_SYNTHETIC_SCENE_RENDERER_H_

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "encoder/src/synthetic/scene_animation.h"
#include "encoder/src/synthetic/scene_content.h"
#include "sdk/src/common/status.h"
#include "sdk/src/gl/egl_context.h"
#include "sdk/src/gl/offscreen_framebuffer.h"
#include "sdk/src/render/camera.h"

namespace m4d {

class SceneRenderer {
 public:
  // Creates a context on the calling thread, which must be the one that renders.
  static Status Create(const SceneContent& content, int width, int height, int supersample,
                       int msaa_samples, std::unique_ptr<SceneRenderer>* renderer);
  ~SceneRenderer();
  SceneRenderer(const SceneRenderer&) = delete;
  SceneRenderer& operator=(const SceneRenderer&) = delete;

  // Draws the visible objects of `state` as `camera` (at the output size) sees them into
  // *rgb: width * height * 3 bytes, row 0 at the top.
  Status Render(const SceneFrameState& state, const Camera& camera, std::vector<uint8_t>* rgb);

  const std::string& description() const { return context_->description(); }

 private:
  struct GpuMesh {
    GLuint vertex_array = 0;
    GLuint buffers[2] = {0, 0};  // vertices, indices
    GLsizei index_count = 0;
  };

  SceneRenderer(int width, int height, int supersample)
      : width_(width), height_(height), supersample_(supersample) {}
  Status Initialize(const SceneContent& content, int msaa_samples);
  GpuMesh Upload(const TriangleMesh& mesh);
  GLuint Upload(const SceneTexture& texture);

  const int width_, height_, supersample_;
  // Declared first so that it is destroyed last, after the GL objects.
  std::unique_ptr<EglContext> context_;
  std::unique_ptr<OffscreenFramebuffer> framebuffer_;
  GLuint program_ = 0;
  GLint uniform_model_ = -1, uniform_view_projection_ = -1, uniform_emissive_ = -1;
  GLint uniform_ambient_ = -1, uniform_sun_direction_ = -1, uniform_sun_colour_ = -1;
  GLint uniform_lamp_position_ = -1, uniform_lamp_colour_ = -1;
  std::vector<GpuMesh> meshes_;       // one per object
  std::vector<GLuint> textures_;      // one per SceneContent texture
  std::vector<int> object_textures_;  // texture index per object
  std::vector<float> object_emissive_;
  std::vector<uint8_t> rgba_;  // the supersampled read-back
};

}  // namespace m4d

#endif  // M4D_ENCODER_SYNTHETIC_SCENE_RENDERER_H_
