// An optional second opinion from a vision-language model through an
// OpenAI-compatible endpoint (POST {endpoint}/chat/completions), as the
// EgoFun3D paper asks one: 2-4 frames (before and after the actuation) with
// the receptor tinted green and the effector magenta, and a prompt asking for
// one of the five effects and one of the four mappings as JSON with reasons.
//
// libcurl is loaded at run time (dlopen "libcurl.so.4"): linking it would
// cost every efc command its start-up time. Built without <curl/curl.h>, the
// adapter reports itself unavailable. Off unless an endpoint is configured;
// an unreachable server, an HTTP error or a reply that is not the JSON asked
// for is a warning, and the data-driven answer stands.
//
// Combination: the answer is a prior over the data's posterior,
//   P(x | data, vlm) ∝ P(x | data) * (w if x is the VLM's choice else (1-w)/(K-1))
// with w = kVlmWeight, for effects (K = 5) and mappings (K = 4) separately.
// The data's evidence is usually decisive (BIC differences of tens); the VLM
// decides what pixels cannot (a heater that never glowed in the clip, a
// press seen once that may latch or count).
#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace efc::pipeline {

constexpr double kVlmWeight = 0.7;

struct VlmAnswer {
  bool ok = false;
  std::string effect, mapping, reasons;
  std::string error;  // when !ok
};

struct VlmRequest {
  std::string endpoint, model, api_key;
  double timeout_s = 60;
  std::string prompt;
  std::vector<std::string> pngs;  // PNG file bytes
};

// The prompt for one function (names of the parts as the recording gives them).
std::string vlm_prompt(const std::string& function, const std::string& receptor, const std::string& effector);

// The chat-completions body: model, temperature 0, one user message whose
// content is the text then each image as a data:image/png;base64 URL.
nlohmann::json vlm_request_body(const VlmRequest& req);

// The answer from a chat-completions reply body: choices[0].message.content
// holding the JSON object (code fences and text around it tolerated).
// Effect and mapping must be among the known names.
VlmAnswer parse_vlm_reply(const std::string& body);

// Whether the adapter can run here (libcurl found); *why otherwise.
bool vlm_available(std::string* why);

// Sends the request and parses the reply; !ok with error on any failure.
VlmAnswer ask_vlm(const VlmRequest& req);

// Folds the answer in as a prior (see above). `effects` in the order
// geometry, illumination, temperature, fluid, airflow; `mappings` binary,
// step, linear, cumulative. Both renormalised.
void combine_with_vlm(const VlmAnswer& answer, std::vector<double>* effects, std::vector<double>* mappings);

std::string base64_encode(const std::string& bytes);

}  // namespace efc::pipeline
