// No command destroys an input and no failed write leaves half a file (util/FileOutput.h): every
// writer under a simulated full disk keeps the old file and leaves no temporary file; protected
// inputs are refused however the output path spells them (relative, "..", symbolic and hard
// links); Scene::inputFiles lists every file a scene reads.
#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <csignal>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <random>
#include <sstream>
#include <thread>

#include "app/commands/Commands.h"
#include "calculation/CalculationGrid.h"
#include "formats/Photometry.h"
#include "luminaires/lightfield/LightField.h"
#include "renderer/ImageFile.h"
#include "report/ComparisonSheet.h"
#include "scene/SceneIo.h"
#include "tests/TempDir.h"
#include "tests/TestUtil.h"
#include "ui/EditorState.h"
#include "util/Error.h"
#include "util/FileOutput.h"

namespace candela {
namespace {

namespace fs = std::filesystem;
using test::inputError;

#define EXPECT_CONTAINS(text, part) \
    EXPECT_NE(std::string(text).find(part), std::string::npos) << "in: " << (text)

/// A file of tests/data (not named data(): ADL would pick std::data for a std::string).
std::string testData(const std::string& relative) {
    return test::dataDir() + "/" + relative;
}

std::string readBytes(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

void writeBytes(const fs::path& path, const std::string& bytes) {
    std::ofstream(path, std::ios::binary) << bytes;
}

using test::TempDir;

/// The old content of a file a writer replaces: larger than kSizeLimit, so a truncation by the
/// failed write would show, and recognisable byte for byte.
std::string oldContent() {
    std::string text;
    for (int i = 0; text.size() < 4000; ++i) text += "old line " + std::to_string(i) + "\n";
    return text;
}

/// Files may not grow past this many bytes in the child: far smaller than every output below
/// (each is over a kilobyte) and than the old files (4000 bytes), so the write fails part-way.
constexpr rlim_t kSizeLimit = 300;

/// Exit codes of runOnFullDisk's child.
enum ChildExit {
    kInputErrorNamingFile = 0,
    kNoError = 1,
    kMessageWithoutFile = 2,
    kOtherException = 3
};

/// fork() copies only the calling thread: a thread pool that OpenImageIO or OpenEXR started for
/// an earlier test in this process has no workers in the child, which would wait for them for
/// ever. While this lives both run in the calling thread. OpenEXR resizes its pool only when a
/// file is opened, so one tiny EXR is encoded here, in the parent, where the workers still exist.
class SingleThreadedImageIo {
  public:
    SingleThreadedImageIo() {
        OIIO::getattribute("threads", mThreads);
        OIIO::getattribute("exr_threads", mExrThreads);
        OIIO::attribute("threads", 1);
        OIIO::attribute("exr_threads", -1);  // -1: no OpenEXR worker threads at all
        float pixel = 0.f;
        encodeImage("pool.exr", 1, 1, 1, &pixel);
    }
    ~SingleThreadedImageIo() {
        OIIO::attribute("threads", mThreads);
        OIIO::attribute("exr_threads", mExrThreads);
    }

  private:
    int mThreads = 0, mExrThreads = 0;
};

/// Runs `write` in a forked child whose files may not grow past kSizeLimit bytes (RLIMIT_FSIZE
/// with SIGXFSZ ignored, so write() fails with EFBIG as on a full disk instead of killing it;
/// unlike a read-only folder this works for root too). Returns the child's exit code: 0 when it
/// threw an InputError whose message names `file`. The limit never touches this process.
/// A child that has not ended after kChildSeconds is killed and the fork tried again (at most
/// three times, then -2): a thread of this process that held the allocator's lock when fork()
/// copied it leaves the child waiting on that lock for ever (seen under AddressSanitizer, whose
/// allocator lock a worker thread of OpenImageIO held, in 2 of 3 CI runs on 2026-11-26).
constexpr int kChildSeconds = 20;  // a child ends within a second when nothing hangs
int runOnFullDiskOnce(const std::function<void()>& write, const std::string& file);
int runOnFullDisk(const std::function<void()>& write, const std::string& file) {
    for (int attempt = 0; attempt < 3; ++attempt) {
        int code = runOnFullDiskOnce(write, file);
        if (code != -2) return code;
        std::fprintf(stderr, "runOnFullDisk: the child hung (a lock copied while held); again\n");
    }
    return -2;
}

int runOnFullDiskOnce(const std::function<void()>& write, const std::string& file) {
    SingleThreadedImageIo noWorkers;
    std::fflush(nullptr);
    pid_t pid = fork();
    if (pid < 0) return -1;
    if (pid == 0) {
        std::signal(SIGXFSZ, SIG_IGN);
        rlimit limit{};
        getrlimit(RLIMIT_FSIZE, &limit);
        limit.rlim_cur = kSizeLimit;
        if (setrlimit(RLIMIT_FSIZE, &limit) != 0) _exit(4);
        int code = kNoError;
        try {
            write();
        } catch (const InputError& e) {
            std::string message = e.what();
            std::fprintf(stderr, "child: %s\n", message.c_str());
            code = message.find(file) != std::string::npos ? kInputErrorNamingFile
                                                           : kMessageWithoutFile;
        } catch (const std::exception& e) {
            std::fprintf(stderr, "child: not an InputError: %s\n", e.what());
            code = kOtherException;
        }
        _exit(code);  // no gtest or static destructors in the child
    }
    int status = 0;
    for (int waited = 0;; ++waited) {
        pid_t done = waitpid(pid, &status, WNOHANG);
        if (done == pid) break;
        if (done < 0 && errno != EINTR) return -1;
        if (waited >= kChildSeconds * 100) {
            kill(pid, SIGKILL);
            while (waitpid(pid, &status, 0) < 0 && errno == EINTR) {
            }
            return -2;
        }
        usleep(10000);
    }
    return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}

/// Random bytes (fixed seed): images of noise, which no format compresses below kSizeLimit.
std::vector<unsigned char> noise8(size_t count) {
    std::mt19937 random(7);
    std::vector<unsigned char> out(count);
    for (unsigned char& v : out) v = static_cast<unsigned char>(random() & 0xff);
    return out;
}

std::vector<float> noiseFloat(size_t count) {
    std::mt19937 random(11);
    std::uniform_real_distribution<float> uniform(0.f, 4.f);
    std::vector<float> out(count);
    for (float& v : out) v = uniform(random);
    return out;
}

/// Runs a writer over `target` (holding oldContent()) on a full disk and checks the contract:
/// an InputError naming the target, the old file byte for byte, no other file in the folder.
void expectFullDiskKeepsOldFile(const TempDir& dir, const fs::path& target,
                                const std::function<void()>& write) {
    writeBytes(target, oldContent());
    std::vector<std::string> before = dir.entries();
    EXPECT_EQ(runOnFullDisk(write, target.filename().string()), kInputErrorNamingFile)
        << "1: no error, 2: an error not naming the file, 3: not an InputError (see the child's "
           "line above)";
    EXPECT_EQ(readBytes(target), oldContent()) << target << " changed";
    EXPECT_EQ(dir.entries(), before) << "a temporary file was left behind";
}

// --- A failed write keeps the old file and leaves nothing --------------------------------------

TEST(FileOutput, TextWriterKeepsTheOldFileOnAFullDisk) {
    TempDir dir;
    fs::path target = dir / "summary.txt";
    std::string text(2000, 'n');
    expectFullDiskKeepsOldFile(dir, target, [&] { writeFileAtomically(target.string(), text); });
}

TEST(FileOutput, PngWriterKeepsTheOldFileOnAFullDisk) {
    // OpenImageIO's PNG writer reports success after a short write; the memory encoding and the
    // checked write() loop are what catch it.
    TempDir dir;
    fs::path target = dir / "render.png";
    std::vector<unsigned char> rgb = noise8(64 * 64 * 3);
    expectFullDiskKeepsOldFile(dir, target, [&] { writeImage8(target.string(), 64, 64, rgb); });
}

TEST(FileOutput, ExrWriterKeepsTheOldFileOnAFullDisk) {
    TempDir dir;
    fs::path target = dir / "render.exr";
    std::vector<float> rgb = noiseFloat(32 * 32 * 3);
    expectFullDiskKeepsOldFile(dir, target, [&] { writeImageFloat(target.string(), 32, 32, rgb); });
}

/// A 2 x 2 light field of 16 x 16 noise images (valid for save()).
std::unique_ptr<LightFieldData> smallLightField() {
    auto lf = std::make_unique<LightFieldData>();
    lf->count = {2, 2};
    lf->spacing = {0.01, 0.01};
    lf->width = lf->height = 16;
    for (int m = 0; m < 4; ++m) lf->images.push_back({noiseFloat(16 * 16), {}});
    return lf;
}

TEST(FileOutput, LightFieldSaveKeepsTheOldFilesOnAFullDisk) {
    TempDir dir;
    std::unique_ptr<LightFieldData> lf = smallLightField();
    // The old light field: its manifest and images, all of which save() would replace.
    for (const char* name : {"lamp_0_0.exr", "lamp_1_0.exr", "lamp_0_1.exr", "lamp_1_1.exr"})
        writeBytes(dir / name, oldContent() + name);
    fs::path target = dir / "lamp.lf.json";
    // The images come first: the first one's failure is what the error names.
    writeBytes(target, oldContent());
    std::vector<std::string> before = dir.entries();
    EXPECT_EQ(runOnFullDisk([&] { lf->save(target); }, "lamp_0_0.exr"), kInputErrorNamingFile);
    EXPECT_EQ(readBytes(target), oldContent());
    for (const char* name : {"lamp_0_0.exr", "lamp_1_0.exr", "lamp_0_1.exr", "lamp_1_1.exr"})
        EXPECT_EQ(readBytes(dir / name), oldContent() + name) << name;
    EXPECT_EQ(dir.entries(), before);
}

TEST(FileOutput, GridCsvKeepsTheOldFileOnAFullDisk) {
    TempDir dir;
    GridResult grid;
    for (int i = 0; i < 10; ++i) grid.u.push_back(0.1 * i), grid.v.push_back(0.2 * i);
    grid.E.assign(100, 123.456);
    grid.stdError.assign(100, 0.5);  // 100 rows of about 60 bytes: some 6 kB of CSV
    grid.initial.assign(100, 154.32);
    fs::path target = dir / "grid.csv";
    expectFullDiskKeepsOldFile(dir, target, [&] { writeGridCsv(target.string(), grid); });

    // Without the limit the same call writes the CSV, header first.
    writeGridCsv(target.string(), grid);
    EXPECT_EQ(readBytes(target).rfind("x,y,z,E_", 0), 0u);
    EXPECT_EQ(dir.entries(), std::vector<std::string>{"grid.csv"});
}

TEST(FileOutput, SceneSaveKeepsTheOldFileOnAFullDisk) {
    TempDir dir;
    Scene scene = loadScene(testData("scenes/roundtrip.json"));
    fs::path target = dir / "scene.json";
    expectFullDiskKeepsOldFile(dir, target, [&] { saveScene(scene, target.string()); });
}

TEST(FileOutput, SheetWriterLeavesNoFileOnAFullDisk) {
    // The sheet (and the screenshots, which share the writers) goes to new names: a failure must
    // leave the folder as it was, the file beside it untouched.
    TempDir dir;
    SheetImage sheet;
    sheet.width = 48;
    sheet.height = 32;
    sheet.display = noise8(48 * 32 * 3);
    sheet.linear = noiseFloat(48 * 32 * 3);
    fs::path beside = dir / "notes.txt";
    writeBytes(beside, oldContent());
    int code = runOnFullDisk([&] { writeSheet(dir.path(), sheet, nullptr); }, "sheet-000.png");
    EXPECT_EQ(code, kInputErrorNamingFile);
    EXPECT_EQ(readBytes(beside), oldContent());
    EXPECT_EQ(dir.entries(), std::vector<std::string>{"notes.txt"});
}

TEST(FileOutput, AHalfWrittenSheetIsTakenBack) {
    // A 1 x 1 sheet: its PNG fits in the disk's room, its EXR (a header of several hundred
    // bytes) and sidecar do not. The PNG already written is removed, so no half sheet is left
    // and the next sheet does not skip a number.
    TempDir dir;
    SheetImage sheet;
    sheet.width = 1;
    sheet.height = 1;
    sheet.display = noise8(3);
    sheet.linear = noiseFloat(3);
    int code = runOnFullDisk([&] { writeSheet(dir.path(), sheet, nullptr); }, "sheet-000.");
    EXPECT_EQ(code, kInputErrorNamingFile);
    EXPECT_EQ(dir.entries(), std::vector<std::string>{});
    SheetFiles next = writeSheet(dir.path(), sheet, nullptr);
    EXPECT_EQ(fs::path(next.png).filename(), "sheet-000.png");
}

TEST(FileOutput, ReplacingKeepsPermissionsAndLeavesNoTemporaryFile) {
    TempDir dir;
    fs::path kept = dir / "private.json";
    writeBytes(kept, oldContent());
    ASSERT_EQ(chmod(kept.c_str(), 0600), 0);
    writeFileAtomically(kept.string(), "new\n");
    EXPECT_EQ(readBytes(kept), "new\n");
    struct stat st {};
    ASSERT_EQ(stat(kept.c_str(), &st), 0);
    EXPECT_EQ(st.st_mode & 07777, 0600u);

    fs::path fresh = dir / "fresh.txt";  // a new file: rw-r--r--, whatever mkstemps gave
    writeFileAtomically(fresh.string(), "x");
    ASSERT_EQ(stat(fresh.c_str(), &st), 0);
    EXPECT_EQ(st.st_mode & 07777, 0644u);
    EXPECT_EQ(dir.entries(), (std::vector<std::string>{"fresh.txt", "private.json"}));
}

TEST(FileOutput, ImagesEncodedInMemoryReadBack) {
    TempDir dir;
    std::vector<unsigned char> rgb8 = noise8(20 * 10 * 3);
    std::vector<float> rgb = noiseFloat(20 * 10 * 3);
    writeImage8((dir / "a.png").string(), 20, 10, rgb8);
    writeImageFloat((dir / "a.exr").string(), 20, 10, rgb);
    int w = 0, h = 0;
    std::vector<float> png = readImageFloat((dir / "a.png").string(), w, h);
    ASSERT_EQ(w, 20);
    ASSERT_EQ(h, 10);
    for (size_t i = 0; i < png.size(); ++i)
        ASSERT_FLOAT_EQ(png[i], rgb8[i] / 255.f) << i;  // 8-bit, lossless
    std::vector<float> exr = readImageFloat((dir / "a.exr").string(), w, h);
    for (size_t i = 0; i < exr.size(); ++i)
        ASSERT_EQ(exr[i], rgb[i]) << i;  // 32-bit float, lossless
    EXPECT_CONTAINS(inputError([&] { writeImage8((dir / "a.jpq").string(), 20, 10, rgb8); }),
                    "a.jpq");
    EXPECT_EQ(dir.entries(), (std::vector<std::string>{"a.exr", "a.png"}));
}

// --- Outputs never replace inputs --------------------------------------------------------------

TEST(ProtectedInputs, RefusesAnInputThroughARelativePath) {
    TempDir dir;
    fs::path input = dir / "scene.json";
    writeBytes(input, oldContent());
    ProtectedInputs inputs({input.string()});
    std::string relative = fs::relative(input, fs::current_path()).string();
    ASSERT_TRUE(fs::path(relative).is_relative()) << relative;
    std::string m = inputError([&] { checkNotAnInput(relative, "--csv"); });
    EXPECT_CONTAINS(m,
                    input.string() + ": --csv " + relative +
                        " would overwrite this input of the command; choose another output file");
    EXPECT_EQ(m.find('\n'), std::string::npos) << "one line";
    // The writer checks again by itself.
    EXPECT_CONTAINS(inputError([&] { writeFileAtomically(relative, "x"); }),
                    "would overwrite this input");
    EXPECT_EQ(readBytes(input), oldContent());
}

TEST(ProtectedInputs, RefusesAnInputThroughDotDot) {
    TempDir dir;
    fs::create_directories(dir / "sub");
    fs::path input = dir / "lamp.ies";
    writeBytes(input, oldContent());
    ProtectedInputs inputs({input.string()});
    std::string viaDotDot = (dir.path() / "sub" / ".." / "lamp.ies").string();
    EXPECT_CONTAINS(inputError([&] { checkNotAnInput(viaDotDot, "--out"); }), "--out " + viaDotDot);
    // A file that does not exist yet is compared by its canonical path.
    ProtectedInputs missing({(dir / "sub/not-yet.csv").string()});
    EXPECT_CONTAINS(
        inputError([&] { checkNotAnInput((dir / "sub/../sub/./not-yet.csv").string()); }),
        "not-yet.csv");
    EXPECT_NO_THROW(checkNotAnInput((dir / "sub/other.csv").string()));
}

TEST(ProtectedInputs, RefusesAnInputThroughSymbolicAndHardLinks) {
    TempDir dir;
    fs::path input = dir / "map.exr";
    writeBytes(input, oldContent());
    fs::create_symlink(input, dir / "link.exr");
    fs::create_hard_link(input, dir / "hard.exr");
    fs::create_directory_symlink(dir.path(), dir / "folder-link");
    {
        ProtectedInputs inputs({input.string()});
        for (const char* name : {"link.exr", "hard.exr", "folder-link/map.exr"}) {
            std::string output = (dir / name).string();
            EXPECT_CONTAINS(inputError([&] { checkNotAnInput(output, "--out"); }),
                            input.string() + ": --out " + output);
            EXPECT_CONTAINS(inputError([&] {
                                writeImageFloat(output, 1, 1, {1.f, 2.f, 3.f});
                            }),
                            output);
        }
    }
    {
        // The input named through the link: its target is protected too.
        ProtectedInputs inputs({(dir / "link.exr").string()});
        EXPECT_CONTAINS(inputError([&] { checkNotAnInput(input.string()); }),
                        "link.exr: writing " + input.string());
    }
    EXPECT_EQ(readBytes(input), oldContent());
    EXPECT_EQ(dir.entries(),
              (std::vector<std::string>{"folder-link", "hard.exr", "link.exr", "map.exr"}));
}

TEST(ProtectedInputs, EveryWriterRefusesAnInput) {
    TempDir dir;
    fs::path text = dir / "a.json", png = dir / "a.png", image = dir / "lamp_1_0.exr",
             csv = dir / "g.csv";
    for (const fs::path& p : {text, png, image, csv}) writeBytes(p, oldContent());
    ProtectedInputs inputs({text.string(), png.string(), image.string(), csv.string()});
    EXPECT_CONTAINS(inputError([&] { writeFileAtomically(text.string(), "x"); }),
                    "a.json: writing");
    EXPECT_CONTAINS(
        inputError([&] { saveScene(loadScene(testData("scenes/roundtrip.json")), text.string()); }),
        "would overwrite this input");
    EXPECT_CONTAINS(
        inputError([&] { writeImage8(png.string(), 2, 1, std::vector<unsigned char>(6, 9)); }),
        "a.png: writing");
    // save() checks every file before writing any: lamp_0_0.exr is not written either.
    std::unique_ptr<LightFieldData> lf = smallLightField();
    EXPECT_CONTAINS(inputError([&] { lf->save(dir / "lamp.lf.json"); }), "lamp_1_0.exr: writing");
    GridResult grid;
    EXPECT_CONTAINS(inputError([&] { writeGridCsv(csv.string(), grid); }), "g.csv: writing");
    for (const fs::path& p : {text, png, image, csv}) EXPECT_EQ(readBytes(p), oldContent()) << p;
    EXPECT_EQ(dir.entries(),
              (std::vector<std::string>{"a.json", "a.png", "g.csv", "lamp_1_0.exr"}));
}

TEST(ProtectedInputs, ScopesForgetTheirFilesAndNest) {
    TempDir dir;
    fs::path a = dir / "a.txt", b = dir / "b.txt";
    writeBytes(a, "a");
    writeBytes(b, "b");
    {
        ProtectedInputs outer({a.string()});
        {
            ProtectedInputs inner({b.string()});
            EXPECT_EQ(protectedInputFor(a.string()), a.string());
            EXPECT_EQ(protectedInputFor(b.string()), b.string());
        }
        EXPECT_EQ(protectedInputFor(b.string()), "");
        EXPECT_EQ(protectedInputFor(a.string()), a.string());
        outer.add((dir / "c.txt").string());
        EXPECT_EQ(protectedInputFor((dir / "c.txt").string()), (dir / "c.txt").string());
    }
    // Nothing outlives its scope: the next test (or command) starts with no protected file.
    EXPECT_EQ(protectedInputFor(a.string()), "");
    writeFileAtomically(a.string(), "new");
    EXPECT_EQ(readBytes(a), "new");
}

TEST(ProtectedInputs, SameFile) {
    TempDir dir;
    writeBytes(dir / "x", "x");
    writeBytes(dir / "y", "y");
    EXPECT_TRUE(sameFile((dir / "x").string(), (dir / "." / "x").string()));
    EXPECT_FALSE(sameFile((dir / "x").string(), (dir / "y").string()));
    EXPECT_FALSE(sameFile((dir / "x").string(), (dir / "missing").string()));
    EXPECT_TRUE(sameFile((dir / "m1").string(), (dir / "sub" / ".." / "m1").string()));
}

TEST(ProtectedInputs, EditorSaveAsRefusesTheFilesTheSceneReadsButItsOwn) {
    TempDir dir;
    fs::create_directories(dir / "state");
    setenv("CANDELA_STATE_DIR", (dir / "state").c_str(), 1);  // the recent-files list goes here
    fs::copy_file(testData("photometric/scene.json"), dir / "scene.json");
    fs::copy_file(testData("photometric/spot.ies"), dir / "spot.ies");
    std::string ies = readBytes(dir / "spot.ies");
    ui::EditorState state;
    ASSERT_TRUE(ui::openSceneFile(state, (dir / "scene.json").string()));
    EXPECT_FALSE(ui::saveSceneFile(state, (dir / "spot.ies").string()));
    EXPECT_TRUE(state.statusIsError);
    EXPECT_CONTAINS(state.status,
                    "spot.ies: Save As " + (dir / "spot.ies").string() +
                        " would overwrite this input of the scene; choose another output file");
    EXPECT_EQ(readBytes(dir / "spot.ies"), ies);
    // Its own file (Save) and a new one (Save As) are fine; nothing stays protected afterwards.
    EXPECT_TRUE(ui::saveSceneFile(state, {}));
    EXPECT_TRUE(ui::saveSceneFile(state, (dir / "copy.json").string()));
    EXPECT_EQ(protectedInputFor((dir / "spot.ies").string()), "");
    unsetenv("CANDELA_STATE_DIR");
}

TEST(ProtectedInputs, TheEditorsOwnSceneIsReplacedOnlyBySaveOnItsThread) {
    // The editor protects every file its scene reads, the scene included, for its whole life
    // (ui/Editor.cpp); only Save, through an InputReplacement on its thread, writes the scene.
    TempDir dir;
    fs::create_directories(dir / "state");
    setenv("CANDELA_STATE_DIR", (dir / "state").c_str(), 1);
    fs::copy_file(testData("photometric/scene.json"), dir / "scene.json");
    fs::copy_file(testData("photometric/spot.ies"), dir / "spot.ies");
    std::string scenePath = (dir / "scene.json").string();
    ui::EditorState state;
    ASSERT_TRUE(ui::openSceneFile(state, scenePath));
    ProtectedInputs editorLifetime(state.scene.inputFiles());
    std::string before = readBytes(dir / "scene.json");
    // The layout file, a screenshot or a report written onto the scene: refused.
    EXPECT_CONTAINS(inputError([&] { writeFileAtomically(scenePath, "{}"); }),
                    "scene.json: writing " + scenePath + " would overwrite this input");
    EXPECT_EQ(readBytes(dir / "scene.json"), before);
    {
        InputReplacement save(scenePath);
        // Another thread (a report being exported) is still refused.
        std::string other;
        std::thread([&] { other = protectedInputFor(scenePath); }).join();
        EXPECT_EQ(other, scenePath);
        // This thread may replace the scene, and nothing else.
        EXPECT_EQ(protectedInputFor(scenePath), "");
        EXPECT_EQ(protectedInputFor((dir / "spot.ies").string()), (dir / "spot.ies").string());
    }
    EXPECT_EQ(protectedInputFor(scenePath), scenePath);  // the replacement ended with its scope
    applyEdit(state, "Move", kChangeLuminaires,
              [](Scene& s) { s.luminaires[0]->pose.position.x += 0.5; });
    EXPECT_TRUE(ui::saveSceneFile(state, {}));
    EXPECT_NE(readBytes(dir / "scene.json"), before);
    unsetenv("CANDELA_STATE_DIR");
}

// --- Scene::inputFiles --------------------------------------------------------------------------

bool listed(const std::vector<std::string>& files, const std::string& path) {
    for (const std::string& f : files)
        if (sameFile(f, path)) return true;
    return false;
}

TEST(SceneInputs, ListsTheSceneItsGltfAndBuffers) {
    Scene scene = loadScene(testData("scenes/roundtrip.json"));
    std::vector<std::string> files = scene.inputFiles();
    EXPECT_TRUE(listed(files, testData("scenes/roundtrip.json")));
    EXPECT_TRUE(listed(files, testData("gltf/triangle.gltf")));
    EXPECT_TRUE(listed(files, testData("gltf/tri.bin")));
    EXPECT_EQ(files.size(), 3u) << "planes, boxes and rectangles read no file";
}

TEST(SceneInputs, ListsALightFieldAndItsImages) {
    Scene scene = loadScene(testData("lightfield/scene.json"));
    std::vector<std::string> files = scene.inputFiles();
    EXPECT_TRUE(listed(files, testData("lightfield/tiny.lf.json")));
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) {
            std::string image =
                "lightfield/tiny_" + std::to_string(i) + "_" + std::to_string(j) + ".exr";
            EXPECT_TRUE(listed(files, testData(image))) << image;
        }
    EXPECT_EQ(files.size(), 11u);  // the scene, the manifest, 9 images
}

TEST(SceneInputs, ListsTheEnvironmentMap) {
    Scene scene = loadScene(testData("environment/constant.json"));
    EXPECT_TRUE(listed(scene.inputFiles(), testData("environment/constant_2.exr")));
    Scene sky = loadScene(testData("environment/sky.json"));
    EXPECT_EQ(sky.inputFiles().size(), 1u) << "a procedural sky reads no file";
}

TEST(SceneInputs, ListsAPhotometricFileAndItsTiltFile) {
    TempDir dir;
    // lambert.ies with its TILT=NONE line replaced by a TILT file beside it (two angles, factor 1).
    std::string ies = readBytes(testData("photometric/lambert.ies"));
    size_t at = ies.find("TILT=NONE");
    ASSERT_NE(at, std::string::npos);
    ies.replace(at, 9, "TILT=lamp.tilt");
    writeBytes(dir / "lamp.ies", ies);
    writeBytes(dir / "lamp.tilt", "1\n2\n0 90\n1 1\n");
    writeBytes(dir / "scene.json",
               R"({"luminaires": [{"type": "photometric", "file": "lamp.ies"}]})");
    Scene scene = loadScene((dir / "scene.json").string());
    std::vector<std::string> files = scene.inputFiles();
    EXPECT_TRUE(listed(files, (dir / "lamp.ies").string()));
    EXPECT_TRUE(listed(files, (dir / "lamp.tilt").string()));
    EXPECT_EQ(files.size(), 3u);
    EXPECT_EQ(loadPhotometry((dir / "lamp.ies").string()).tiltPath, (dir / "lamp.tilt").string());
}

}  // namespace
}  // namespace candela
