// Which particle fields a writer writes: the scene's "fields" list, or every
// field the stages marked for output. Resolved once in open(); "position" is
// always written (as coordinates) and never listed here.
#pragma once

#include <string_view>
#include <vector>

#include "talus/particles.hpp"

namespace talus {
class ParamSet;
class ParamValues;
}  // namespace talus

namespace talus::writers {

// Declares the common "fields" parameter (optional string list).
void declare_fields_parameter(ParamSet& p);

// The fields of `store` to write. With a "fields" list, an unknown name is an
// InputError pointing at /fields (when `strict`) or skipped (a second store,
// e.g. the wall particles, that lacks some of them). Particle writers keep
// the identity fields (id, body) with any list, so particles can still be
// followed and told apart; a sampler (probes) passes `identity` false.
std::vector<FieldInfo> select_fields(const ParticleStore& store, const ParamValues& params, bool strict,
                                     bool identity = true);

// "a, b, c" of the store's field names, for messages.
std::string field_names(const ParticleStore& store);

}  // namespace talus::writers
