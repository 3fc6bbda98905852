#include "cropsight/io/voc.hpp"

#include <gtest/gtest.h>

#include <fstream>

#include "cropsight/core/error.hpp"
#include "testing/testing.hpp"

namespace {
using cropsight::Error;
using cropsight::testing::error_message;
using cropsight::testing::TempDir;
namespace io = cropsight::io;

using cropsight::testing::write_text;

std::string box_xml(const std::string& xmin, const std::string& ymin, const std::string& xmax,
                    const std::string& ymax) {
  return "<object><name>potato</name><bndbox><xmin>" + xmin + "</xmin><xmax>" + xmax + "</xmax><ymin>" + ymin +
         "</ymin><ymax>" + ymax + "</ymax></bndbox></object>";
}

TEST(Voc, ReadsFilenameSizeAndObjects) {
  TempDir t;
  write_text(t / "a.xml",
             "<?xml version=\"1.0\"?>\n<annotation><filename>a.jpg</filename>"
             "<size><width>416</width><height>400</height><depth>3</depth></size>" +
                 box_xml("113", "98", "141", "162") +
                 "<object><name> potato </name><difficult>1</difficult><bndbox><xmin>1.5</xmin>"
                 "<ymin>2</ymin><xmax>3</xmax><ymax>4</ymax></bndbox></object></annotation>");
  const io::VocAnnotation a = io::read_voc(t / "a.xml");
  EXPECT_EQ(a.filename, "a.jpg");
  EXPECT_EQ(a.width, 416);
  EXPECT_EQ(a.height, 400);
  EXPECT_EQ(a.depth, 3);
  ASSERT_EQ(a.objects.size(), 2u);
  EXPECT_EQ(a.objects[0].name, "potato");
  EXPECT_EQ(a.objects[0].xmin, 113);
  EXPECT_EQ(a.objects[0].ymin, 98);
  EXPECT_EQ(a.objects[0].xmax, 141);  // xmax before ymin in the file: read by name, not order
  EXPECT_EQ(a.objects[0].ymax, 162);
  EXPECT_FALSE(a.objects[0].difficult);
  EXPECT_EQ(a.objects[1].name, "potato");
  EXPECT_DOUBLE_EQ(a.objects[1].xmin, 1.5);
  EXPECT_TRUE(a.objects[1].difficult);
}

TEST(Voc, BadFilesNameFileAndElement) {
  TempDir t;
  const auto head = std::string("<annotation><filename>a.jpg</filename>");
  write_text(t / "broken.xml", head + "<object><name>potato</name>");  // unclosed
  write_text(t / "missing.xml", head +
                                    "<object><name>potato</name><bndbox><xmin>1</xmin><ymin>1</ymin><xmax>2</xmax>"
                                    "</bndbox></object></annotation>");
  write_text(t / "text.xml", head + box_xml("1", "1", "abc", "2") + "</annotation>");
  write_text(t / "reversed.xml", head + box_xml("1", "1", "2", "2") + box_xml("5", "1", "4", "2") + "</annotation>");
  write_text(t / "root.xml", "<html></html>");
  const std::string e1 = error_message([&] { io::read_voc(t / "broken.xml"); });
  EXPECT_NE(e1.find("broken.xml: malformed XML"), std::string::npos) << e1;
  const std::string e2 = error_message([&] { io::read_voc(t / "missing.xml"); });
  EXPECT_NE(e2.find("missing.xml: object 1 <bndbox>: missing <ymax>"), std::string::npos) << e2;
  const std::string e3 = error_message([&] { io::read_voc(t / "text.xml"); });
  EXPECT_NE(e3.find("text.xml: object 1 <bndbox>: <xmax> is not a number ('abc')"), std::string::npos) << e3;
  const std::string e4 = error_message([&] { io::read_voc(t / "reversed.xml"); });
  EXPECT_NE(e4.find("reversed.xml: object 2 <bndbox>: <xmax> is less than <xmin>"), std::string::npos) << e4;
  const std::string e5 = error_message([&] { io::read_voc(t / "root.xml"); });
  EXPECT_NE(e5.find("root.xml: root element is <html>"), std::string::npos) << e5;
  const std::string e6 = error_message([&] { io::read_voc(t / "absent.xml"); });
  EXPECT_NE(e6.find("absent.xml"), std::string::npos) << e6;
}

TEST(DetectionText, ReadsThePapersFormat) {
  TempDir t;
  write_text(t / "a.txt", "potato 0.99349546 98 208 143 298\n\npotato 0.91259694 7 128 38 180\r\n");
  const auto d = io::read_detection_text(t / "a.txt");
  ASSERT_EQ(d.size(), 2u);
  EXPECT_EQ(d[0].label, "potato");
  EXPECT_DOUBLE_EQ(d[0].score, 0.99349546);
  EXPECT_EQ(d[0].x1, 98);
  EXPECT_EQ(d[0].y1, 208);
  EXPECT_EQ(d[0].x2, 143);
  EXPECT_EQ(d[0].y2, 298);
  EXPECT_EQ(d[1].y2, 180);
}

TEST(DetectionText, BadLinesNameFileAndLine) {
  TempDir t;
  write_text(t / "few.txt", "potato 0.9 1 2 3 4\npotato 0.9 1 2 3\n");
  write_text(t / "nan.txt", "potato 0.9 1 2 x 4\n");
  write_text(t / "rev.txt", "\n\npotato 0.9 5 2 3 4\n");
  EXPECT_NE(error_message([&] { io::read_detection_text(t / "few.txt"); }).find("few.txt: line 2: expected 6 fields"),
            std::string::npos);
  EXPECT_NE(error_message([&] { io::read_detection_text(t / "nan.txt"); }).find("nan.txt: line 1: x2 is not a number"),
            std::string::npos);
  EXPECT_NE(error_message([&] { io::read_detection_text(t / "rev.txt"); }).find("rev.txt: line 3: x2 is less than x1"),
            std::string::npos);
}

TEST(DetectionText, WriteReadsBack) {
  TempDir t;
  std::vector<cropsight::Detection2D> dets(2);
  dets[0] = {10.5f, 20, 30, 40.25f, 0, 0.87654321f};
  dets[1] = {1, 2, 3, 4, 3, 0.5f};
  io::write_detection_text(t / "o.txt", dets, {"potato"});
  const auto back = io::read_detection_text(t / "o.txt");
  ASSERT_EQ(back.size(), 2u);
  EXPECT_EQ(back[0].label, "potato");
  EXPECT_EQ(back[1].label, "class3");
  EXPECT_NEAR(back[0].score, 0.87654321, 1e-7);
  EXPECT_DOUBLE_EQ(back[0].x1, 10.5);
  EXPECT_DOUBLE_EQ(back[0].y2, 40.25);
}

}  // namespace
