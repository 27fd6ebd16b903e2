// Binary codec of a search chain's state (optimize/search/search.hpp ChainState) for messages
// between ranks (optimize/search/island_search): exact (doubles as bits, the generator as its
// textual state), so a chain decoded on another rank continues exactly as it would have. The
// checkpoint file is JSON (io/checkpoint).
#pragma once

#include <vector>

#include "optimize/search/byte_codec.hpp"
#include "optimize/search/search.hpp"

namespace pinmask {

void encode_pattern(ByteWriter& w, const Pattern& p);
Pattern decode_pattern(ByteReader& r);

void encode_chain_state(ByteWriter& w, const ChainState& s);
ChainState decode_chain_state(ByteReader& r);

Bytes encode_chain_states(const std::vector<ChainState>& states);
std::vector<ChainState> decode_chain_states(const Bytes& bytes);

}  // namespace pinmask
