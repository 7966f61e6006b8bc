#pragma once
// What the bag harnesses share: a visitor that decodes every message of a topic with the
// definition the bag carries (all fields walked, none kept), so that the container readers and
// the message decoder are exercised together. A DecodeError or an odocal::Error is the
// documented outcome for bad bytes.

#include <map>
#include <memory>
#include <optional>

#include "odocal/bag/bag_reader.hpp"
#include "odocal/bag/message_decoder.hpp"
#include "odocal/error.hpp"

namespace odocal::fuzz {

class DecodingVisitor : public bag::BagVisitor {
 public:
  void topic(std::size_t index, const bag::BagTopic& topic) override {
    decoders_[index].reset();
    try {
      decoders_[index].emplace(topic.type, topic.definition, topic.definition_format,
                               bag::message_encoding_from_name(topic.encoding, topic.name),
                               std::vector<std::string>{}, topic.name);
    } catch (const odocal::Error&) {
      // A topic whose type cannot be decoded is listed, not imported.
    }
  }

  void message(const bag::BagMessage& message) override {
    const auto decoder = decoders_.find(message.topic);
    if (decoder == decoders_.end() || !decoder->second) return;
    try {
      decoder->second->decode(message.data, fields_);
    } catch (const bag::DecodeError&) {
    }
  }

 private:
  std::map<std::size_t, std::optional<bag::MessageDecoder>> decoders_;
  bag::DecodedFields fields_;
};

}  // namespace odocal::fuzz
