#pragma once

#include <stdexcept>

namespace tilejet::synth {

// Every failure the synth library reports to a user: bad exemplar, bad parameters,
// unreadable or damaged texture map. The message names the file or parameter.
class SynthError : public std::runtime_error {
  public:
    using std::runtime_error::runtime_error;
};

}  // namespace tilejet::synth
