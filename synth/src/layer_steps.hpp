#pragma once

// Tone steps where the layers of a quilted canvas meet, removed in the gradient domain (Pérez,
// Gangnet and Blake 2003, "Poisson image editing"; Kwatra et al. 2003 stitch graph-cut patches
// so). A cut between two copies of the stone is as good as its pixels along it, but where the
// two copies differ in tone over a region, the whole cut shows as a soft line: in a cell image
// that is every cut of its blocks into its frame strips, at nearly the same place in every cell,
// and a wall of them showed the cell grid as lines 2 to 10 px inside every border (the corpus's
// wood, slate and marble: tilejet eval's lines along the cell grid 1.67, 1.27, 1.18).
// Removed (`map build --smooth-steps`), wood's lines fall to 1.21 and slate's to 1.14, and the
// squares a wall showed at half size go; but the copies are no longer exact: the smooth drift,
// about 1 dE, invisible side by side, is all texture energy sees (limestone 3.45 times
// quilting's against 1.10, wood 1.36 against 0.49). Not the default while the gates count it.

#include <opencv2/core/mat.hpp>
#include <vector>

namespace tilejet::synth::detail {

// One of the copies a canvas is quilted from: canvas pixel p shows image pixel p + offset
// wherever the layer was cut in, and the layer has values for every canvas pixel of `area`.
struct CanvasLayer {
    const cv::Mat* image = nullptr;  // CV_8UC3
    cv::Point offset;
    cv::Rect area;
    // Steps are removed only between layers of different kinds: in a cell image, its frame
    // strips (0) and its own blocks (1), whose cuts run at nearly the same place in every cell;
    // the blocks' cuts among themselves wander, and spread over the insides they cost the
    // copies' exactness for nothing (slate's texture energy 2.06 against 1.87).
    int kind = 0;
};

// Changes `rgb` (CV_8UC3) so that across each pair of neighbours showing layers of different
// kinds (`layer_of`, CV_32S indices into `layers`; negative: none) the change is what the two
// layers themselves show there (their mean, of those that have both pixels), and elsewhere what it
// was, as nearly as a least-squares fit allows with the pixels of `fixed` (CV_8U, non-zero)
// kept exactly. The difference a step made is spread smoothly over the layers' insides.
void remove_layer_steps(cv::Mat& rgb, const cv::Mat& layer_of,
                        const std::vector<CanvasLayer>& layers, const cv::Mat& fixed);

}  // namespace tilejet::synth::detail
