// [creases] / [ridges] normalisation in a scene file: "thirds" (default) and "paper" are read into
// CreaseParams, anything else is a one-line scene error naming both values.
#include <filesystem>

#include <gtest/gtest.h>

#include "../cli/cli_support.hpp"
#include "core/error.hpp"
#include "scene/scene.hpp"

using namespace penink;
using namespace penink::test;
namespace fs = std::filesystem;

namespace {

std::string scene_text(const std::string& creases) {
    return "[terrain]\ndem = \"" PENINK_SOURCE_DIR "/examples/volcano.asc\"\n[creases]\n" + creases +
           "[ridges]\nnormalisation = \"paper\"\n";
}

}  // namespace

TEST(CreaseNormalisationScene, ReadsBothNamesAndDefaultsToThirds) {
    const fs::path dir = fresh_dir("crease_normalisation");
    write_text(dir / "a.toml", scene_text("normalisation = \"paper\"\nmin_score = 0.8\n"));
    write_text(dir / "b.toml", scene_text("min_score = 0.8\n"));
    const Scene a = load_scene((dir / "a.toml").string()), b = load_scene((dir / "b.toml").string());
    EXPECT_EQ(a.lines.creases.normalisation, ScoreNormalisation::paper);
    EXPECT_EQ(b.lines.creases.normalisation, ScoreNormalisation::thirds);
    EXPECT_EQ(b.lines.ridges.normalisation, ScoreNormalisation::paper);
    fs::remove_all(dir);
}

TEST(CreaseNormalisationScene, UnknownNameIsAnError) {
    const fs::path dir = fresh_dir("crease_normalisation_bad");
    write_text(dir / "bad.toml", scene_text("normalisation = \"mean\"\n"));
    std::string message = "no error";
    try {
        load_scene((dir / "bad.toml").string());
    } catch (const Error& e) {
        message = e.what();
    }
    EXPECT_NE(message.find("[creases] normalisation must be \"thirds\", \"paper\" or \"rank\" (got \"mean\")"), std::string::npos)
        << message;
    fs::remove_all(dir);
}
