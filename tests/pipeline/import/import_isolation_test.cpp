// import_asset runs importers in a child process: what the importer reads is the same as
// in-process, and what kills an importer (these hand-written files crash or exhaust Debian's
// Assimp 5.2) becomes a one-line input error naming the file and the importer.
#include <gtest/gtest.h>

#include <fstream>

#include "asset/asset_wire.h"
#include "asset_paths.h"
#include "crowdbake/pipeline/error.h"
#include "crowdbake/pipeline/import.h"
#include "gltf_test_builder.h"
#include "pipeline_calls.h"
#include "temp_dir.h"

namespace crowdbake {
namespace {

using test::TempDir;

// Triangle index and weight joint far outside their arrays: Assimp's MD5 loader writes
// through them.
const char* const kOverflowingMd5 = R"(MD5Version 10
commandline ""
numJoints 1
numMeshes 1
joints {
	"root"	-1 ( 0 0 0 ) ( 0 0 0 )
}
mesh {
	shader "x"
	numverts 3
	vert 0 ( 0 0 ) 0 1
	vert 1 ( 0 0 ) 1 1
	vert 2 ( 0 0 ) 2 1
	numtris 1
	tri 0 0 1 400000000
	numweights 3
	weight 0 0 1.0 ( 0 0 0 )
	weight 1 400000000 1.0 ( 1 0 0 )
	weight 2 400000000 1.0 ( 0 1 0 )
}
)";

// An OFF header declaring two billion vertices: the loader reserves them up front.
const char* const kAbsurdOff = "OFF\n2000000000 1 0\n0 0 0\n";

std::string write_text(const TempDir& dir, const std::string& name, const char* text) {
  const auto path = dir / name;
  std::ofstream(path, std::ios::binary) << text;
  return path.string();
}

Error import_error(const std::string& path, const ImportOptions& options = {}) {
  try {
    test::import_or_throw(path, options);
  } catch (const Error& e) {
    return e;
  }
  ADD_FAILURE() << path << " imported";
  return input_error("", "");
}

TEST(ImportIsolation, ACrashingImporterIsAnInputError) {
  TempDir dir;
  const std::string path = write_text(dir, "overflow.md5mesh", kOverflowingMd5);
  const Error e = import_error(path);
  EXPECT_EQ(e.kind(), Error::Kind::kInput);
  EXPECT_TRUE(test::names_file(e, path)) << e.what();
  const std::string message = e.what();
  EXPECT_NE(message.find("Assimp importer crashed"), std::string::npos) << message;
  EXPECT_NE(message.find("re-export"), std::string::npos) << message;
  EXPECT_EQ(message.find('\n'), std::string::npos) << "one line";
}

TEST(ImportIsolation, AnAbsurdAllocationStopsAtTheMemoryLimit) {
  TempDir dir;
  const std::string path = write_text(dir, "absurd.off", kAbsurdOff);
  ImportOptions options;
  options.limits.memory_mib = 1024;
  const std::string message = import_error(path, options).what();
  EXPECT_NE(message.find("memory limit (1024 MiB)"), std::string::npos) << message;
  EXPECT_NE(message.find("--import-memory"), std::string::npos) << message;
}

TEST(ImportIsolation, TheImporterInTheChildReadsWhatItReadsHere) {
  TempDir dir;
  const auto path = test::two_bone_character().write(dir / "c.gltf").string();
  ImportOptions here;
  here.limits.isolate = false;
  EXPECT_EQ(encode_asset(test::import_or_throw(path)),
            encode_asset(test::import_or_throw(path, here)));
}

TEST(ImportIsolation, ASharedFbxReadsTheSameIsolatedOrNot) {
  CROWDBAKE_REQUIRE_SHARED_ASSETS();
  const std::string path = (test::shared_assets() / "Quaternius_Zombie/Zombie.fbx").string();
  ImportOptions here;
  here.limits.isolate = false;
  EXPECT_EQ(encode_asset(test::import_or_throw(path)),
            encode_asset(test::import_or_throw(path, here)));
}

TEST(ImportIsolation, InputErrorsOfTheImporterKeepTheirMessage) {
  TempDir dir;
  const std::string path = write_text(dir, "broken.gltf", R"({"asset": {"version": "2.0"}})");
  ImportOptions here;
  here.limits.isolate = false;
  const std::string isolated = import_error(path).what();
  EXPECT_EQ(isolated, std::string(import_error(path, here).what()));
}

}  // namespace
}  // namespace crowdbake
