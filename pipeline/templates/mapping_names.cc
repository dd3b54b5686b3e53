#include "pipeline/templates/mapping_names.h"

#include <map>

#include "pipeline/templates/effect_names.h"

namespace efc::pipeline {
namespace {

// Words that name one mapping each: the receptors whose kind fixes how they
// map. Left out on purpose: "knob", "dial", "lever", "handle", "crank",
// "button", "paddle" (each comes as a switch, a selector, a control and a
// stepper).
const std::map<std::string, int>& lexicon() {
  static const std::map<std::string, int> words = [] {
    std::map<std::string, int> w;
    for (const char* s : {"door", "lid", "drawer", "hatch", "flap", "cover", "gate", "switch", "toggle", "rocker",
                          "interlock"})
      w[s] = 0;
    for (const char* s : {"slider", "slide", "fader", "wheel", "handwheel", "thumbwheel", "mixer", "dimmer",
                          "throttle", "rheostat"})
      w[s] = 2;
    for (const char* s : {"plus", "minus", "up", "down", "increase", "decrease", "increment", "decrement", "more",
                          "less"})
      w[s] = 3;
    return w;
  }();
  return words;
}

}  // namespace

int mapping_named(const std::string& receptor) { return last_named_in(lexicon(), receptor); }

}  // namespace efc::pipeline
