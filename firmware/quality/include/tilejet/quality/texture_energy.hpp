#pragma once

// Texture energy (docs/design.md section 8; Kwatra et al. 2005): how far the output's small
// neighbourhoods are from anything in the exemplar. Copy-based output is made of exemplar
// pieces, so away from seams it is near 0; seams and foreign content raise it.
//
// Measured that way alone (coherence), an output that copies one calm corner of the exemplar
// over and over scores best: quilting does that on marble, a wallpaper of one motif whose
// veins are gone. The other direction (completeness: how far the exemplar's neighbourhoods are
// from anything in the output; Simakov et al. 2008, "bidirectional similarity") catches it.
// Indexing the output instead of the exemplar measures it with the same class.

#include <cstdint>
#include <memory>
#include <opencv2/core/mat.hpp>
#include <vector>

namespace tilejet::quality {

inline constexpr int kEnergyPatch = 8;
// Every position of images up to this many patches in all (the corpus: a stretch of wall of
// 1 Mpx, exemplars up to 1000 px); beyond, every n-th position, and each sample is searched at
// the n x n shifts from it, one of which lies on the grid wherever a copy is. Session 26 found
// the coarser grid alone (every third position, unshifted) put a floor of about 4 under
// completeness: an exemplar patch copied off the grid met only misaligned neighbours.
// Indexing 4 million patches instead cost the 200-tile eval 4 minutes more.
inline constexpr size_t kEnergyMaxPatches = 1100000;

class TextureEnergy {
  public:
    // Indexes the 8x8 CIELab patches of `exemplar` (CV_8UC3 R,G,B) at every position (on a
    // coarser grid searched at every shift, beyond kEnergyMaxPatches), reduced by PCA to 24
    // dimensions for an OpenCV FLANN kd-forest; `threads` searches run side by side.
    explicit TextureEnergy(const cv::Mat& exemplar, int threads = 0);
    // The patches of several images (e.g. a wall's tiles), `max_patches` at most in all (on a
    // coarser grid searched at every shift, beyond): each costs about 110 bytes, and the index a
    // second or so per 100 000 to build.
    explicit TextureEnergy(const std::vector<cv::Mat>& images, int threads = 0,
                           size_t max_patches = kEnergyMaxPatches);
    ~TextureEnergy();
    TextureEnergy(const TextureEnergy&) = delete;
    TextureEnergy& operator=(const TextureEnergy&) = delete;

    // Mean over `samples` 8x8 patches of `tiles`, at uniformly random positions (seeded), of
    // the per-pixel RMS CIELab distance (Delta E 1976) to the nearest exemplar patch: the
    // approximate search proposes 4 candidates in PCA space, the exact 192-value distance
    // picks among them. A random sample of patches estimates the mean over all pixels; with
    // 3e4 samples its standard error (about 0.01) is far below the differences that matter.
    double measure(const std::vector<cv::Mat>& tiles, size_t samples, uint64_t seed) const;

  private:
    struct Index;
    std::unique_ptr<Index> index_;
};

}  // namespace tilejet::quality
