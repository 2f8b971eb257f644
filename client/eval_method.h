#pragma once
// A method of `strata eval --methods`: a method the server offers, optionally with ReSTIR flags of
// its own, written NAME[:FLAG=VALUE]... (a flag without a value is a switch, such as no-spatial):
//   restir-splat:disocclusion-initial-candidates=8
//   restir-multilayer:reveal-lookahead=0:silhouette-band=2
// so that variants of one method run side by side in one evaluation, in the same interleaved
// timing rounds (the equal-time baselines of ML Fig. 9). The entry is the run's name in every
// output; its flags override those given to the whole evaluation.
#include <string>

#include "restir_flags.h"

namespace strata::client {

struct EvalMethod {
  std::string method;  // the server's method (CreateSessionRequest.method)
  RestirFlags restir;  // the evaluation's ReSTIR flags with the entry's own applied
};

// Throws std::runtime_error naming the entry and the flag it could not take.
EvalMethod parse_eval_method(const std::string& entry, const RestirFlags& common);

}  // namespace strata::client
