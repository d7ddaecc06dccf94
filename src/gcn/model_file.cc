#include "gcn/model_file.h"

#include <cstring>
#include <map>

#include "util/binary_io.h"
#include "util/error.h"
#include "util/file.h"

namespace colmap_gcn {
namespace {

constexpr char kMagic[8] = {'C', 'G', 'C', 'N', 'M', 'O', 'D', 'L'};
constexpr size_t kHeaderSize = 24;

static_assert(sizeof(float) == 4, "float must be 32-bit");

bool IsLittleEndian() {
  const uint16_t one = 1;
  unsigned char byte;
  std::memcpy(&byte, &one, 1);
  return byte == 1;
}

// A ByteWriter with the model file's tagged sections.
class Writer : public ByteWriter {
 public:
  void PutSection(const char tag[4], const std::string& body) {
    Bytes().append(tag, 4);
    Put<uint64_t>(body.size());
    Bytes().append(body);
  }
};

// A ByteReader over one section; running out of it, or a value it cannot
// hold, is "GCN model file <source>: malformed <what> section".
class Reader : public ByteReader {
 public:
  Reader(const std::string& bytes,
         size_t begin,
         size_t end,
         const std::string& source,
         const std::string& what)
      : ByteReader(
            bytes,
            begin,
            end,
            [source, what](size_t) {
              ThrowError(
                  "GCN model file ", source, ": malformed ", what, " section");
            }),
        source_(source) {}

  int GetPositiveInt(const char* name, int max_value) {
    const int32_t value = Get<int32_t>();
    if (value <= 0 || value > max_value) {
      ThrowError("GCN model file ",
                 source_,
                 " has an invalid ",
                 name,
                 " (",
                 value,
                 ")");
    }
    return value;
  }
  void ExpectEnd() {
    if (Remaining() != 0) Fail();
  }
  // Fails unless exactly `count` floats are left, before anything is
  // allocated for them (sizes come from the file).
  void ExpectFloatsLeft(uint64_t count) {
    if (count != Remaining() / sizeof(float) ||
        Remaining() % sizeof(float) != 0) {
      Fail();
    }
  }

 private:
  std::string source_;
};

}  // namespace

uint64_t Fnv1a64(const char* data, size_t size) {
  uint64_t hash = 14695981039346656037ull;
  for (size_t i = 0; i < size; ++i) {
    hash ^= static_cast<unsigned char>(data[i]);
    hash *= 1099511628211ull;
  }
  return hash;
}

std::string SerializeGcnModel(const GcnModel& model) {
  if (!IsLittleEndian())
    ThrowError("GCN model files need a little-endian host");
  model.Check();
  Writer payload;
  {
    Writer s;
    s.PutString(model.embedding.type);
    s.Put<int32_t>(model.EmbeddingDim());
    s.PutString(model.embedding.blob);
    payload.PutSection("EMBD", s.Bytes());
  }
  {
    Writer s;
    s.Put<int32_t>(model.shape.input_dim);
    s.Put<int32_t>(model.shape.NumGcnLayers());
    for (int dim : model.shape.gcn_dims) s.Put<int32_t>(dim);
    s.Put<int32_t>(model.shape.fc_dim);
    s.Put<int32_t>(static_cast<int32_t>(model.aggregation));
    payload.PutSection("NETS", s.Bytes());
  }
  // Only when not the default, so models without it stay byte-identical.
  if (model.feature_scaling != QesFeatureScaling::kNone) {
    Writer s;
    s.Put<int32_t>(static_cast<int32_t>(model.feature_scaling));
    payload.PutSection("FEAT", s.Bytes());
  }
  if (model.structure_features != QesStructureFeatures::kNone) {
    Writer s;
    s.Put<int32_t>(static_cast<int32_t>(model.structure_features));
    payload.PutSection("STRC", s.Bytes());
  }
  {
    Writer s;
    s.PutFloats(model.input_shift.data(), model.input_shift.size());
    s.PutFloats(model.input_scale.data(), model.input_scale.size());
    payload.PutSection("NORM", s.Bytes());
  }
  {
    Writer s;
    s.Put<uint64_t>(model.params.Size());
    s.PutFloats(model.params.Values().data(), model.params.Size());
    payload.PutSection("WGTS", s.Bytes());
  }
  {
    Writer s;
    s.Put<float>(model.info.tau_mo);
    s.Put<float>(model.info.tau_ct);
    s.Put<int32_t>(model.info.test_k1);
    s.Put<int32_t>(model.info.test_k2);
    s.Put<int32_t>(model.info.test_u);
    s.Put<float>(model.info.threshold);
    payload.PutSection("INFO", s.Bytes());
  }
  {
    Writer s;
    s.PutString(model.info.notes);
    payload.PutSection("NOTE", s.Bytes());
  }
  Writer file;
  file.Bytes().append(kMagic, sizeof(kMagic));
  file.Put<uint32_t>(kGcnModelFormatVersion);
  file.Put<uint32_t>(0);
  file.Put<uint64_t>(payload.Bytes().size());
  file.Bytes().append(payload.Bytes());
  file.Put<uint64_t>(Fnv1a64(payload.Bytes().data(), payload.Bytes().size()));
  return file.Bytes();
}

namespace {

// Checks the header, size and checksum; returns the payload's size.
uint64_t CheckModelFileFrame(const std::string& bytes,
                             const std::string& source) {
  if (!IsLittleEndian())
    ThrowError("GCN model files need a little-endian host");
  if (bytes.size() < sizeof(kMagic) ||
      std::memcmp(bytes.data(), kMagic, sizeof(kMagic)) != 0) {
    ThrowError(source, " is not a GCN model file (bad magic)");
  }
  if (bytes.size() < kHeaderSize) {
    ThrowError(
        "GCN model file ", source, " is truncated (", bytes.size(), " bytes)");
  }
  uint32_t version;
  std::memcpy(&version, bytes.data() + 8, 4);
  if (version != kGcnModelFormatVersion) {
    ThrowError("GCN model file ",
               source,
               " has format version ",
               version,
               "; this build reads version ",
               kGcnModelFormatVersion);
  }
  uint64_t payload_size;
  std::memcpy(&payload_size, bytes.data() + 16, 8);
  const uint64_t expected_size = kHeaderSize + payload_size + 8;
  if (payload_size > bytes.size() || bytes.size() < expected_size) {
    ThrowError("GCN model file ",
               source,
               " is truncated (",
               bytes.size(),
               " of ",
               expected_size,
               " bytes)");
  }
  if (bytes.size() > expected_size) {
    ThrowError("GCN model file ",
               source,
               " has ",
               bytes.size() - expected_size,
               " trailing bytes");
  }
  uint64_t checksum;
  std::memcpy(&checksum, bytes.data() + kHeaderSize + payload_size, 8);
  if (checksum != Fnv1a64(bytes.data() + kHeaderSize, payload_size)) {
    ThrowError("GCN model file ", source, " is corrupt (checksum mismatch)");
  }
  return payload_size;
}

// The payload's tagged sections, each read through its own bounded Reader.
class ModelSections {
 public:
  ModelSections(const std::string& bytes,
                uint64_t payload_size,
                const std::string& source)
      : bytes_(bytes), source_(source) {
    size_t pos = kHeaderSize;
    const size_t end = kHeaderSize + payload_size;
    while (pos < end) {
      if (end - pos < 12) {
        ThrowError("GCN model file ", source, ": malformed section header");
      }
      const std::string tag = bytes.substr(pos, 4);
      uint64_t length;
      std::memcpy(&length, bytes.data() + pos + 4, 8);
      pos += 12;
      if (length > end - pos) {
        ThrowError("GCN model file ",
                   source,
                   ": section ",
                   tag,
                   " overruns the payload");
      }
      sections_[tag] = {pos, pos + length};
      pos += length;
    }
  }

  bool Has(const char* tag) const { return sections_.count(tag) > 0; }

  Reader Open(const char* tag) const {
    auto it = sections_.find(tag);
    if (it == sections_.end()) {
      ThrowError("GCN model file ", source_, " lacks the ", tag, " section");
    }
    return Reader(bytes_, it->second.first, it->second.second, source_, tag);
  }

  // An optional one-value section: absent = 0; values above `max` unknown.
  int OptionalEnum(const char* tag, int max, const char* what) const {
    if (!Has(tag)) return 0;
    Reader r = Open(tag);
    const int32_t value = r.Get<int32_t>();
    if (value < 0 || value > max) {
      ThrowError(
          "GCN model file ", source_, " has an unknown ", what, " ", value);
    }
    r.ExpectEnd();
    return static_cast<int>(value);
  }

  const std::string& Source() const { return source_; }

 private:
  const std::string& bytes_;
  const std::string& source_;
  std::map<std::string, std::pair<size_t, size_t>> sections_;
};

void ReadNetworkSection(const ModelSections& sections, GcnModel* model) {
  Reader r = sections.Open("NETS");
  model->shape.input_dim = r.GetPositiveInt("input dimension", 1 << 20);
  const int layers = r.GetPositiveInt("layer count", 64);
  model->shape.gcn_dims.clear();
  for (int l = 0; l < layers; ++l) {
    model->shape.gcn_dims.push_back(r.GetPositiveInt("layer size", 1 << 16));
  }
  model->shape.fc_dim = r.GetPositiveInt("FC size", 1 << 16);
  const int32_t aggregation = r.Get<int32_t>();
  if (aggregation != 0 && aggregation != 1) {
    ThrowError("GCN model file ",
               sections.Source(),
               " has an unknown aggregation ",
               aggregation);
  }
  model->aggregation = static_cast<GcnAggregation>(aggregation);
  r.ExpectEnd();
}

// EMBD, read after the network and the structural features it must fit.
void ReadEmbeddingSection(const ModelSections& sections, GcnModel* model) {
  Reader r = sections.Open("EMBD");
  model->embedding.type = r.GetString();
  model->embedding.dim = r.Get<int32_t>();
  model->embedding.blob = r.GetString();
  r.ExpectEnd();
  if (model->embedding.dim != model->EmbeddingDim()) {
    ThrowError("GCN model file ",
               sections.Source(),
               ": embedding dimension ",
               model->embedding.dim,
               " does not fit the network input ",
               model->shape.input_dim,
               " with ",
               QesStructureFeaturesName(model->structure_features),
               " structural features");
  }
}

// NORM and WGTS, whose sizes follow from the network shape.
void ReadParameterSections(const ModelSections& sections, GcnModel* model) {
  {
    Reader r = sections.Open("NORM");
    r.ExpectFloatsLeft(2 * static_cast<uint64_t>(model->shape.input_dim));
    model->input_shift.resize(model->shape.input_dim);
    model->input_scale.resize(model->shape.input_dim);
    r.GetFloats(model->input_shift.data(), model->shape.input_dim);
    r.GetFloats(model->input_scale.data(), model->shape.input_dim);
    r.ExpectEnd();
  }
  Reader r = sections.Open("WGTS");
  const uint64_t count = r.Get<uint64_t>();
  const size_t needed = GcnParameterLayout(model->shape).size;
  if (count != needed) {
    ThrowError("GCN model file ",
               sections.Source(),
               " has ",
               count,
               " weights but its network shape needs ",
               needed);
  }
  r.ExpectFloatsLeft(count);
  model->params = GcnParameters<float>(model->shape);
  r.GetFloats(model->params.Values().data(), count);
  r.ExpectEnd();
}

// INFO and the optional NOTE.
void ReadInfoSections(const ModelSections& sections, GcnModel* model) {
  {
    Reader r = sections.Open("INFO");
    model->info.tau_mo = r.Get<float>();
    model->info.tau_ct = r.Get<float>();
    model->info.test_k1 = r.Get<int32_t>();
    model->info.test_k2 = r.Get<int32_t>();
    model->info.test_u = r.Get<int32_t>();
    model->info.threshold = r.Get<float>();
    r.ExpectEnd();
  }
  if (sections.Has("NOTE")) {
    Reader r = sections.Open("NOTE");
    model->info.notes = r.GetString();
    r.ExpectEnd();
  }
}

}  // namespace

GcnModel DeserializeGcnModel(const std::string& bytes,
                             const std::string& source) {
  const uint64_t payload_size = CheckModelFileFrame(bytes, source);
  const ModelSections sections(bytes, payload_size, source);
  GcnModel model;
  ReadNetworkSection(sections, &model);
  model.feature_scaling = static_cast<QesFeatureScaling>(
      sections.OptionalEnum("FEAT", 1, "feature scaling"));
  model.structure_features = static_cast<QesStructureFeatures>(
      sections.OptionalEnum("STRC", 2, "structural node feature set"));
  ReadEmbeddingSection(sections, &model);
  ReadParameterSections(sections, &model);
  ReadInfoSections(sections, &model);
  model.source = source;
  try {
    model.Check();
  } catch (const Error& error) {
    ThrowError("GCN model file ", source, ": ", error.what());
  }
  return model;
}

void WriteGcnModel(const std::string& path, const GcnModel& model) {
  WriteFileAtomically(path, SerializeGcnModel(model));
}

GcnModel ReadGcnModel(const std::string& path) {
  if (!ExistsFile(path)) ThrowError("GCN model file ", path, " does not exist");
  return DeserializeGcnModel(ReadTextFile(path), path);
}

}  // namespace colmap_gcn
