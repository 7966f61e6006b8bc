// Reading ROS bags (issue 18's target: >= 200 MB/s of uncompressed message data on one core):
// 100 000 sensor_msgs/Imu messages (~330 bytes each) read and decoded (stamp, yaw rate, two
// accelerations) from an MCAP file in memory (messages outside chunks, in a stored chunk, lz4
// and zstd chunks) and from a ROS 1 bag (stored chunks).

#include <benchmark/benchmark.h>

#include <algorithm>
#include <cstring>
#include <optional>
#include <string>
#include <vector>

#include "../tests/bag/mcap_builder.hpp"
#include "odocal/bag/bag_reader.hpp"
#include "odocal/bag/message_decoder.hpp"

namespace {

using namespace odocal::bag;

constexpr int kMessages = 100'000;

void put_bytes(std::vector<std::uint8_t>& out, const void* data, std::size_t size) {
  const std::size_t old = out.size();
  out.resize(old + size);
  std::memcpy(out.data() + old, data, size);
}
template <class T>
void put(std::vector<std::uint8_t>& out, T value) {
  put_bytes(out, &value, sizeof(T));
}
void put_doubles(std::vector<std::uint8_t>& out, int count, double value) {
  for (int i = 0; i < count; ++i) put(out, value);
}

// sensor_msgs/msg/Imu in CDR: stamp, frame id "imu_link", then 8-aligned doubles.
std::vector<std::uint8_t> cdr_imu(int k) {
  std::vector<std::uint8_t> out = {0, 1, 0, 0};
  put<std::int32_t>(out, 1000 + k / 100);
  put<std::uint32_t>(out, static_cast<std::uint32_t>(k % 100) * 10'000'000u);
  put<std::uint32_t>(out, 9);
  put_bytes(out, "imu_link", 9);
  while ((out.size() - 4) % 8 != 0) out.push_back(0);
  put_doubles(out, 4, 0.5);
  put_doubles(out, 9, 0.0);
  put_doubles(out, 3, 0.01 * k);
  put_doubles(out, 9, 0.0);
  put_doubles(out, 3, 1.0);
  put_doubles(out, 9, 0.0);
  return out;
}

// The same in ROS 1 serialisation: seq, stamp, frame id, packed doubles.
std::vector<std::uint8_t> ros1_imu(int k) {
  std::vector<std::uint8_t> out;
  put<std::uint32_t>(out, static_cast<std::uint32_t>(k));
  put<std::uint32_t>(out, static_cast<std::uint32_t>(1000 + k / 100));
  put<std::uint32_t>(out, static_cast<std::uint32_t>(k % 100) * 10'000'000u);
  put<std::uint32_t>(out, 8);
  put_bytes(out, "imu_link", 8);
  put_doubles(out, 4, 0.5);
  put_doubles(out, 9, 0.0);
  put_doubles(out, 3, 0.01 * k);
  put_doubles(out, 9, 0.0);
  put_doubles(out, 3, 1.0);
  put_doubles(out, 9, 0.0);
  return out;
}

std::vector<std::uint8_t> mcap_bag(const std::string& layout) {
  odocal::testing::McapBuilder builder;
  builder.schema(1, "sensor_msgs/msg/Imu", "ros2msg", "");
  builder.channel(1, 1, "/imu/data", "cdr");
  const bool chunked = layout != "unchunked";
  for (int k = 0; k < kMessages; ++k) {
    if (chunked && k % 10'000 == 0) builder.begin_chunk();
    builder.message(1, static_cast<std::uint64_t>(k) * 10'000'000u, cdr_imu(k));
    if (chunked && k % 10'000 == 9'999) builder.end_chunk(layout == "stored" ? "" : layout);
  }
  return builder.finish();
}

// A ROS 1 bag (format 2.0) without index: header record, then stored chunks of a connection
// record and message records.
std::vector<std::uint8_t> ros1_bag() {
  const auto field = [](std::vector<std::uint8_t>& out, const std::string& name, const void* value,
                        std::size_t size) {
    put<std::uint32_t>(out, static_cast<std::uint32_t>(name.size() + 1 + size));
    put_bytes(out, name.data(), name.size());
    out.push_back('=');
    put_bytes(out, value, size);
  };
  const auto record = [](std::vector<std::uint8_t>& out, const std::vector<std::uint8_t>& header,
                         const std::vector<std::uint8_t>& data) {
    put<std::uint32_t>(out, static_cast<std::uint32_t>(header.size()));
    put_bytes(out, header.data(), header.size());
    put<std::uint32_t>(out, static_cast<std::uint32_t>(data.size()));
    put_bytes(out, data.data(), data.size());
  };
  std::vector<std::uint8_t> out;
  put_bytes(out, "#ROSBAG V2.0\n", 13);
  {
    std::vector<std::uint8_t> header;
    const std::uint8_t op = 0x03;
    const std::uint64_t index = 0;
    const std::uint32_t zero = 0;
    field(header, "op", &op, 1);
    field(header, "index_pos", &index, 8);
    field(header, "conn_count", &zero, 4);
    field(header, "chunk_count", &zero, 4);
    // rosbag pads the header record to 4096 bytes so that it can be rewritten in place.
    std::vector<std::uint8_t> padding;
    padding.resize(4088 - std::min<std::size_t>(header.size(), 4088));
    std::memset(padding.data(), ' ', padding.size());
    record(out, header, padding);
  }
  const std::string definition =
      "Header header\ngeometry_msgs/Quaternion orientation\nfloat64[9] orientation_covariance\n"
      "geometry_msgs/Vector3 angular_velocity\nfloat64[9] angular_velocity_covariance\n"
      "geometry_msgs/Vector3 linear_acceleration\nfloat64[9] linear_acceleration_covariance\n"
      "================================================================================\n"
      "MSG: std_msgs/Header\nuint32 seq\ntime stamp\nstring frame_id\n"
      "================================================================================\n"
      "MSG: geometry_msgs/Quaternion\nfloat64 x\nfloat64 y\nfloat64 z\nfloat64 w\n"
      "================================================================================\n"
      "MSG: geometry_msgs/Vector3\nfloat64 x\nfloat64 y\nfloat64 z\n";
  const std::uint32_t conn = 0;
  for (int first = 0; first < kMessages; first += 10'000) {
    std::vector<std::uint8_t> chunk;
    {
      std::vector<std::uint8_t> header, data;
      const std::uint8_t op = 0x07;
      field(header, "op", &op, 1);
      field(header, "conn", &conn, 4);
      field(header, "topic", "/imu/data", 9);
      field(data, "topic", "/imu/data", 9);
      field(data, "type", "sensor_msgs/Imu", 15);
      field(data, "md5sum", "6a62c6daae103f4ff57a132d6f95cec2", 32);
      field(data, "message_definition", definition.data(), definition.size());
      record(chunk, header, data);
    }
    for (int k = first; k < first + 10'000; ++k) {
      std::vector<std::uint8_t> header;
      const std::uint8_t op = 0x02;
      const std::uint32_t time[2] = {static_cast<std::uint32_t>(1000 + k / 100),
                                     static_cast<std::uint32_t>(k % 100) * 10'000'000u};
      field(header, "op", &op, 1);
      field(header, "conn", &conn, 4);
      field(header, "time", time, 8);
      record(chunk, header, ros1_imu(k));
    }
    std::vector<std::uint8_t> header;
    const std::uint8_t op = 0x05;
    const auto size = static_cast<std::uint32_t>(chunk.size());
    field(header, "op", &op, 1);
    field(header, "compression", "none", 4);
    field(header, "size", &size, 4);
    record(out, header, chunk);
  }
  return out;
}

class DecodingCounter : public BagVisitor {
 public:
  void topic(std::size_t, const BagTopic& topic) override {
    decoder_.emplace(topic.type, topic.definition, topic.definition_format,
                     message_encoding_from_name(topic.encoding, topic.name),
                     std::vector<std::string>{"header.stamp", "angular_velocity.z",
                                              "linear_acceleration.x", "linear_acceleration.y"},
                     topic.name);
  }
  void message(const BagMessage& message) override {
    decoder_->decode(message.data, fields_);
    sum_ += fields_.numbers[1][0];
    bytes_ += message.data.size();
  }
  double sum_{};
  std::uint64_t bytes_{};

 private:
  std::optional<MessageDecoder> decoder_;
  DecodedFields fields_;
};

void run(benchmark::State& state, const std::vector<std::uint8_t>& bag, bool ros1) {
  std::uint64_t bytes = 0;
  for (auto _ : state) {
    DecodingCounter counter;
    if (ros1) {
      read_ros1_bag(bag, "bench.bag", counter);
    } else {
      read_mcap(bag, "bench.mcap", counter);
    }
    benchmark::DoNotOptimize(counter.sum_);
    bytes += counter.bytes_;
  }
  state.SetBytesProcessed(static_cast<std::int64_t>(bytes));
}

void BM_ReadMcapImu(benchmark::State& state, const std::string& layout) {
  run(state, mcap_bag(layout), false);
}
BENCHMARK_CAPTURE(BM_ReadMcapImu, unchunked, std::string("unchunked"))
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_ReadMcapImu, stored, std::string("stored"))->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_ReadMcapImu, lz4, std::string("lz4"))->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_ReadMcapImu, zstd, std::string("zstd"))->Unit(benchmark::kMillisecond);

void BM_ReadRos1BagImu(benchmark::State& state) { run(state, ros1_bag(), true); }
BENCHMARK(BM_ReadRos1BagImu)->Unit(benchmark::kMillisecond);

}  // namespace
