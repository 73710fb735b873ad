#pragma once
// The largest message taken on each channel, checked on the size a message declares before any
// of it is copied (UdpmReceiver, BusReceiver). Each is a few times the largest legitimate message
// of the model, so that every honest message passes and a flood of oversize ones costs nothing.
#include <cstddef>
#include <string>
#include <vector>

#include "bus/messages.hpp"

namespace tongue::bus {

// How many times the largest legitimate message a channel's limit is.
inline constexpr std::size_t kLimitFactor = 4;
// Floor of the activation limit [bytes]: room for a model with few muscles to grow names.
inline constexpr std::size_t kMinActivationLimit = 4096;
// Commands: the longest name ("shutdown", "describe") makes a 33-byte message.
inline constexpr std::size_t kCommandLimit = 1024;
// Models before one is known [bytes]: rest positions (24 B per node), elements (32 B per hex8),
// muscles, landmarks, and the scene's text, itself at most common::kMaxInputFileBytes (16 MiB).
// The refined tongue's (refinement 2, 6825 nodes) is about 350 kB; 64 MiB is room for a scene
// file at its limit and a mesh of a million nodes.
inline constexpr std::size_t kModelLimit = std::size_t{64} << 20;
// States before the model is known [bytes]: 28 B per node sent; the refined tongue's is about
// 190 kB. Once a model is known, state_limit(model) replaces it.
inline constexpr std::size_t kStateLimitBeforeModel = std::size_t{32} << 20;
// Rejection notices (lcmt_tongue_rejection): the fixed fields, a sender of at most
// kMaxSenderBytes (the server sends none for a longer one), a kind and a one-line reason whose
// quoted names are cut (common::untrusted_text): under 2 kB.
inline constexpr std::size_t kRejectionLimit = 8192;
// Room for the status string in a state's limit [bytes] (the server's status is a line of text).
inline constexpr std::size_t kStatusAllowance = 65536;

// The limit of activations to a model with these muscles: kLimitFactor times a message naming
// all of them with the longest sender (at least kMinActivationLimit).
std::size_t activation_limit(const std::vector<std::string>& muscle_names);

// The limit of states of model: kLimitFactor times a state carrying all its nodes and muscles,
// every node in contact, plus kStatusAllowance.
std::size_t state_limit(const tongue_lcm::lcmt_tongue_model& model);

}  // namespace tongue::bus
