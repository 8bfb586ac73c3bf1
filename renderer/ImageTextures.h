#pragma once
// The editor's small pictures (library thumbnails, the environment's sample chart) as GL
// textures for Dear ImGui. They live here, in the renderer's layer: the UI names them by a key
// and never owns a GL object.

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "renderer/gl/GlObjects.h"

namespace candela {

class ImageTextures {
  public:
    struct Shown {
        uint64_t id = 0;  ///< The GL texture name, as ImGui::Image takes it; 0: none.
        int width = 0, height = 0;
    };

    /// Uploads width x height RGB8 pixels (rgb.size() == 3 width height) under key, replacing
    /// what was there.
    void upload(const std::string& key, int width, int height,
                const std::vector<unsigned char>& rgb);
    /// The texture under key; id 0 when there is none.
    Shown find(const std::string& key) const;

  private:
    std::map<std::string, gl::Texture2D> mTextures;
};

}  // namespace candela
