// The VLAD model file:
//   char[8]  magic "CGCNVLAD"
//   uint32   version (1)
//   uint32   num_words, descriptor_dim, output_dim
//   float32  codebook[num_words][descriptor_dim]
//   float32  pca_mean[num_words * descriptor_dim]
//   float32  eigenvalues[output_dim]
//   float32  projection[output_dim][num_words * descriptor_dim]
//   uint64   checksum: HashBytes (retrieval/hash.h) of all bytes before it
// Little-endian (the machine's layout; x86-64 and arm64 both are).
#include <cstring>

#include "retrieval/hash.h"
#include "retrieval/vlad.h"
#include "util/error.h"
#include "util/file.h"

namespace colmap_gcn {
namespace {

const char kMagic[8] = {'C', 'G', 'C', 'N', 'V', 'L', 'A', 'D'};
const uint32_t kVersion = 1;

template <typename T>
void Append(std::string* out, const T& value) {
  out->append(reinterpret_cast<const char*>(&value), sizeof(T));
}

void AppendFloats(std::string* out, const float* data, size_t count) {
  out->append(reinterpret_cast<const char*>(data), count * sizeof(float));
}

}  // namespace

std::string VladEmbedding::SerializePayload() const {
  std::string out(kMagic, sizeof(kMagic));
  Append(&out, kVersion);
  Append(&out, static_cast<uint32_t>(NumWords()));
  Append(&out, static_cast<uint32_t>(DescriptorDim()));
  Append(&out, static_cast<uint32_t>(OutputDim()));
  AppendFloats(&out, codebook_.data(), codebook_.size());
  AppendFloats(&out, pca_.mean.data(), pca_.mean.size());
  AppendFloats(&out, pca_.eigenvalues.data(), pca_.eigenvalues.size());
  AppendFloats(&out, pca_.projection.data(), pca_.projection.size());
  return out;
}

std::string VladEmbedding::Serialize() const {
  std::string contents = SerializePayload();
  Append(&contents, checksum_);
  return contents;
}

void VladEmbedding::Write(const std::string& path) const {
  WriteFileAtomically(path, Serialize());
}

VladEmbedding VladEmbedding::Read(const std::string& path) {
  if (!ExistsFile(path)) {
    ThrowError("VLAD embedding file ", path, " does not exist");
  }
  return Deserialize(ReadTextFile(path), path);
}

VladEmbedding VladEmbedding::Deserialize(const std::string& contents,
                                         const std::string& source) {
  const std::string& path = source;
  const size_t header_size = sizeof(kMagic) + 4 * sizeof(uint32_t);
  if (contents.size() < sizeof(kMagic) ||
      std::memcmp(contents.data(), kMagic, sizeof(kMagic)) != 0) {
    ThrowError(path, " is not a colmap-gcn VLAD embedding file (bad magic)");
  }
  if (contents.size() < header_size) {
    ThrowError("VLAD embedding file ", path, " is truncated");
  }
  uint32_t header[4];
  std::memcpy(header, contents.data() + sizeof(kMagic), sizeof(header));
  const uint32_t version = header[0];
  const uint64_t num_words = header[1];
  const uint64_t descriptor_dim = header[2];
  const uint64_t output_dim = header[3];
  if (version != kVersion) {
    ThrowError("VLAD embedding file ",
               path,
               " has version ",
               version,
               "; this build reads version ",
               kVersion);
  }
  const uint64_t vlad_dim = num_words * descriptor_dim;
  if (num_words == 0 || num_words > 65536 || descriptor_dim == 0 ||
      descriptor_dim > 4096 || output_dim == 0 || output_dim > vlad_dim) {
    ThrowError("VLAD embedding file ", path, " has invalid dimensions");
  }
  const uint64_t num_floats =
      vlad_dim + vlad_dim + output_dim + output_dim * vlad_dim;
  const uint64_t expected =
      header_size + num_floats * sizeof(float) + sizeof(uint64_t);
  if (contents.size() != expected) {
    ThrowError("VLAD embedding file ",
               path,
               contents.size() < expected ? " is truncated" : " is too long",
               " (",
               contents.size(),
               " bytes, expected ",
               expected,
               ")");
  }
  uint64_t stored_checksum;
  std::memcpy(&stored_checksum,
              contents.data() + expected - sizeof(uint64_t),
              sizeof(uint64_t));
  if (HashBytes(contents.data(), expected - sizeof(uint64_t)) !=
      stored_checksum) {
    ThrowError("VLAD embedding file ", path, " is corrupt (checksum mismatch)");
  }
  const float* data =
      reinterpret_cast<const float*>(contents.data() + header_size);
  // memcpy-based copies: the float data need not be aligned in the string.
  auto read_floats = [&data](float* out, size_t count) {
    std::memcpy(out, data, count * sizeof(float));
    data += count;
  };
  FloatMatrix codebook(num_words, descriptor_dim);
  read_floats(codebook.data(), codebook.size());
  PcaWhitening pca;
  pca.mean.resize(vlad_dim);
  read_floats(pca.mean.data(), pca.mean.size());
  pca.eigenvalues.resize(output_dim);
  read_floats(pca.eigenvalues.data(), pca.eigenvalues.size());
  pca.projection.resize(output_dim, vlad_dim);
  read_floats(pca.projection.data(), pca.projection.size());
  VladEmbedding embedding(std::move(codebook), std::move(pca));
  THROW_CHECK(embedding.Checksum() == stored_checksum);
  return embedding;
}

}  // namespace colmap_gcn
