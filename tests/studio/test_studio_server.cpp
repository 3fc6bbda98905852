// The studio server over real HTTP (httplib::Client on the loopback): who may talk to it, which
// files it serves, what it does with bad bodies, and that labels land in the sequence whole.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <thread>

#include "cropsight/core/error.hpp"
#include "cropsight/io/image_io.hpp"
#include "cropsight/io/sequence.hpp"
#include "studio_fixture.hpp"

namespace cropsight::studio_testing {

namespace fs = std::filesystem;

namespace {

studio::StudioOptions options_for(const fs::path& seq) {
  studio::StudioOptions o;
  o.sequence = seq;
  o.max_body_bytes = 1u << 20;
  return o;
}

// Every file under `dir` with its size, to prove a request wrote nothing there.
std::map<std::string, std::uintmax_t> listing(const fs::path& dir) {
  std::map<std::string, std::uintmax_t> out;
  for (const auto& e : fs::recursive_directory_iterator(dir))
    out[e.path().string()] = e.is_regular_file() ? e.file_size() : 0;
  return out;
}

// {"heads": [[start, length, ...], ...]} for square heads of side `side` at (x, y) each.
std::string heads_body(const std::vector<std::pair<int, int>>& corners, int side, int width) {
  nlohmann::json heads = nlohmann::json::array();
  for (const auto& [x, y] : corners) {
    nlohmann::json runs = nlohmann::json::array();
    for (int r = 0; r < side; ++r) runs.insert(runs.end(), {(y + r) * width + x, side});
    heads.push_back(runs);
  }
  return nlohmann::json{{"heads", heads}}.dump();
}

}  // namespace

TEST(StudioServer, RefusesRequestsWithoutTheToken) {
  testing::TempDir dir;
  RunningStudio studio(options_for(unlabelled_copy(dir.path())));
  auto anonymous = studio.anonymous();
  EXPECT_EQ(anonymous.Get("/api/info")->status, 403);
  EXPECT_EQ(anonymous.Get("/")->status, 403);
  EXPECT_EQ(anonymous.Get("/api/info?token=0123456789abcdef0123456789abcdef")->status, 403);
  EXPECT_EQ(anonymous.Get("/api/info", {{"X-Cropsight-Token", "wrong"}})->status, 403);
  EXPECT_EQ(anonymous.Post("/api/frame/0/labels", "{\"heads\": []}", "application/json")->status, 403);

  // The printed URL: the token turns into a cookie, and the cookie alone is then enough.
  const auto first = anonymous.Get("/?token=" + studio.server().token());
  ASSERT_EQ(first->status, 303);
  const std::string set_cookie = first->get_header_value("Set-Cookie");
  EXPECT_NE(set_cookie.find("HttpOnly"), std::string::npos);
  EXPECT_NE(set_cookie.find("SameSite=Strict"), std::string::npos);
  const std::string cookie = set_cookie.substr(0, set_cookie.find(';'));
  EXPECT_EQ(anonymous.Get("/api/info", {{"Cookie", cookie}})->status, 200);
  EXPECT_EQ(studio.client().Get("/api/info")->status, 200);
}

TEST(StudioServer, RefusesForeignHostHeaders) {
  testing::TempDir dir;
  RunningStudio studio(options_for(unlabelled_copy(dir.path())));
  auto client = studio.client();
  const std::string port = std::to_string(studio.server().port());
  for (const std::string& host : std::vector<std::string>{"evil.example:" + port, "127.0.0.1", "localhost:1",
                                                          "127.0.0.1.evil.example:" + port, "192.168.1.2:" + port})
    EXPECT_EQ(client.Get("/api/info", {{"Host", host}})->status, 403) << host;
  for (const std::string& host : std::vector<std::string>{"localhost:" + port, "127.0.0.1:" + port, "[::1]:" + port})
    EXPECT_EQ(client.Get("/api/info", {{"Host", host}})->status, 200) << host;
}

TEST(StudioServer, ServesOnlyFilesInsideTheSequence) {
  testing::TempDir dir;
  const fs::path seq = unlabelled_copy(dir.path());
  testing::write_text(dir / "secret.txt", "outside the sequence");
  fs::create_directory_symlink(dir.path(), seq / "depth_link");
  fs::create_symlink(dir / "secret.txt", seq / "notes.txt");
  RunningStudio studio(options_for(seq));
  auto client = studio.client();
  EXPECT_EQ(client.Get("/files/camera.yaml")->status, 200);
  EXPECT_EQ(client.Get("/files/depth/000001.png")->status, 200);
  for (const std::string& path : std::vector<std::string>{
           "/files/../secret.txt", "/files/%2e%2e/secret.txt", "/files/%2E%2E%2Fsecret.txt", "/files/..%2fsecret.txt",
           "/files/depth/../../secret.txt", "/files/" + (dir / "secret.txt").string(), "/files//etc/passwd",
           "/files/%2fetc%2fpasswd", "/files/depth_link/secret.txt", "/files/notes.txt",
           "/files/.cropsight-studio.lock", "/files/depth", "/files/%252e%252e/secret.txt", "/../secret.txt",
           "/files/depth\\..\\..\\secret.txt"}) {
    const auto r = client.Get(path);
    ASSERT_TRUE(r) << path;
    EXPECT_GE(r->status, 400) << path;
    EXPECT_LT(r->status, 500) << path;
    EXPECT_EQ(r->body.find("outside the sequence"), std::string::npos) << path;
  }
}

TEST(StudioServer, RefusesOversizedAndMalformedBodies) {
  testing::TempDir dir;
  const fs::path seq = unlabelled_copy(dir.path());
  RunningStudio studio(options_for(seq));
  auto client = studio.client();
  const auto before = listing(dir.path());
  EXPECT_EQ(client.Post("/api/frame/0/labels", std::string(2u << 20, ' '), "application/json")->status, 413);
  for (const std::string& body :
       std::vector<std::string>{"", "{", "[]", "null", "{\"heads\": 3}", "{\"heads\": [[0]]}", "{\"heads\": [[0, 0]]}",
                                "{\"heads\": [[-1, 5]]}", "{\"heads\": [[217000, 1000]]}", "{\"heads\": [[0, 1e30]]}",
                                "{\"heads\": [[\"0\", 1]]}", "{\"heads\": [[0, 9999999999999]]}"})
    EXPECT_EQ(client.Post("/api/frame/0/labels", body, "application/json")->status, 400) << body;
  EXPECT_EQ(client.Post("/api/frame/99/labels", "{\"heads\": []}", "application/json")->status, 404);
  EXPECT_EQ(client.Post("/api/frame/99999999999999/labels", "{\"heads\": []}", "application/json")->status, 404);
  EXPECT_EQ(client.Post("/api/train", "not json", "application/json")->status, 400);
  auto after = listing(dir.path());
  after.erase((seq / ".cropsight-studio.lock").string());
  auto expected = before;
  expected.erase((seq / ".cropsight-studio.lock").string());
  EXPECT_EQ(after, expected);
}

TEST(StudioServer, ConcurrentSavesLeaveOneWholeFrame) {
  testing::TempDir dir;
  const fs::path seq = unlabelled_copy(dir.path());
  const io::SequenceReader original(seq);
  const int width = original.info().camera.width;
  RunningStudio studio(options_for(seq));
  std::vector<std::string> bodies;
  for (int k = 0; k < 8; ++k) bodies.push_back(heads_body({{10 + 20 * k, 10}, {10 + 20 * k, 60}}, 12, width));
  std::vector<std::thread> threads;
  std::vector<int> statuses(bodies.size());
  for (std::size_t k = 0; k < bodies.size(); ++k)
    threads.emplace_back(
        [&, k] { statuses[k] = studio.client().Post("/api/frame/1/labels", bodies[k], "application/json")->status; });
  for (auto& t : threads) t.join();
  for (int s : statuses) EXPECT_EQ(s, 200);

  // The frame holds exactly one of the saves: two heads of 144 pixels at one body's corners.
  const io::SequenceReader reader(seq);
  EXPECT_EQ(reader.info().labelled_frames, std::vector<int>{1});
  const LabelImage labels = reader.read(1).labels;
  std::map<int, int> sizes;
  int first_x = -1;
  for (std::size_t p = 0; p < labels.size(); ++p)
    if (labels.data[p]) {
      ++sizes[labels.data[p]];
      if (first_x < 0) first_x = int(p % std::size_t(width));
    }
  ASSERT_EQ(sizes.size(), 2u);
  for (const auto& [id, n] : sizes) EXPECT_EQ(n, 144);
  EXPECT_EQ((first_x - 10) % 20, 0);
  const auto& truth = reader.groundtruth();
  ASSERT_EQ(truth.instances.size(), 2u);
  for (const auto& t : truth.instances) EXPECT_TRUE(sizes.count(t.id)) << t.id;
  EXPECT_FALSE(reader.read(0).labels.size());  // frame 0 is not labelled
  // No temporary left beside the written files.
  for (const auto& e : fs::recursive_directory_iterator(seq))
    EXPECT_EQ(e.path().filename().string().find(".tmp"), std::string::npos) << e.path();
  EXPECT_FALSE(fs::exists(dir.path().parent_path() / "labels"));
}

TEST(StudioServer, AKillBetweenImageAndListHealsAtTheNextStart) {
  testing::TempDir dir;
  const fs::path seq = unlabelled_copy(dir.path());
  const int width = io::SequenceReader(seq).info().camera.width;
  {
    RunningStudio studio(options_for(seq));
    ASSERT_EQ(studio.client().Post("/api/frame/2/labels", heads_body({{5, 5}}, 4, width), "application/json")->status,
              200);
  }
  // As if killed after labels/000002.png was renamed and before labelled.csv was.
  testing::write_text(seq / "labelled.csv", "frame\n");
  EXPECT_THROW(io::SequenceReader{seq}, Error);
  RunningStudio again(options_for(seq));
  EXPECT_EQ(nlohmann::json::parse(again.client().Get("/api/info")->body)["labelled"], nlohmann::json({2}));
  EXPECT_EQ(io::SequenceReader(seq).info().labelled_frames, std::vector<int>{2});
}

TEST(StudioServer, SecondStudioOnASequenceIsReadOnly) {
  testing::TempDir dir;
  const fs::path seq = unlabelled_copy(dir.path());
  const int width = io::SequenceReader(seq).info().camera.width;
  {
    RunningStudio first(options_for(seq));
    RunningStudio second(options_for(seq));
    EXPECT_TRUE(first.server().writable());
    EXPECT_FALSE(second.server().writable());
    EXPECT_EQ(second.client().Post("/api/frame/0/labels", heads_body({{5, 5}}, 4, width), "application/json")->status,
              403);
    EXPECT_TRUE(nlohmann::json::parse(second.client().Get("/api/info")->body)["read_only"].get<bool>());
    EXPECT_EQ(first.client().Post("/api/frame/0/labels", heads_body({{5, 5}}, 4, width), "application/json")->status,
              200);
  }
  EXPECT_FALSE(fs::exists(seq / ".cropsight-studio.lock"));  // released by the first studio's stop
  RunningStudio again(options_for(seq));
  EXPECT_TRUE(again.server().writable());
  auto read_only = options_for(seq);
  read_only.read_only = true;
  RunningStudio viewer(read_only);
  EXPECT_FALSE(viewer.server().writable());
}

}  // namespace cropsight::studio_testing
