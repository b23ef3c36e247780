// Strict parsing of option values (tools/gsresample/strict_parse.h).
#include <limits>
#include <string>

#include <gtest/gtest.h>

#include <tools/gsresample/strict_parse.h>

using gsresample::ParseChoice;
using gsresample::ParseDouble;
using gsresample::ParseInt;
using gsresample::Quoted;

namespace {

const double kInfinity = std::numeric_limits<double>::infinity();

void ExpectIntRefused(const std::string &text, int min, int max, const std::string &reason)
{
    int value = 1234;
    std::string error;
    EXPECT_FALSE(ParseInt(text, min, max, value, error)) << text;
    EXPECT_EQ(value, 1234) << "left unchanged on failure: " << text;
    EXPECT_NE(error.find(reason), std::string::npos) << error;
}

void ExpectDoubleRefused(const std::string &text, double min, double max, const std::string &reason)
{
    double value = 12.5;
    std::string error;
    EXPECT_FALSE(ParseDouble(text, min, max, value, error)) << text;
    EXPECT_EQ(value, 12.5) << "left unchanged on failure: " << text;
    EXPECT_NE(error.find(reason), std::string::npos) << error;
}

} // namespace

TEST(StrictParse, IntInRangeIsParsed)
{
    int value = 0;
    std::string error;
    EXPECT_TRUE(ParseInt("42", 2, 256, value, error));
    EXPECT_EQ(value, 42);
    EXPECT_TRUE(ParseInt("-7", -10, 10, value, error));
    EXPECT_EQ(value, -7);
    EXPECT_TRUE(ParseInt("+256", 2, 256, value, error));
    EXPECT_EQ(value, 256);
    EXPECT_TRUE(ParseInt("2147483647", 0, std::numeric_limits<int>::max(), value, error));
    EXPECT_EQ(value, std::numeric_limits<int>::max());
}

TEST(StrictParse, IntWithJunkIsRefused)
{
    for (const char *text : {"abc", "", " 5", "5 ", "5x", "0x10", "1.5", "1e3", "--5", "+"})
        ExpectIntRefused(text, 0, 1000, "expected an integer between 0 and 1000");
    ExpectIntRefused(std::string("5\0" "7", 3), 0, 1000, "expected an integer");
}

TEST(StrictParse, IntOutOfRangeIsRefused)
{
    ExpectIntRefused("99999999999", 2, 256, "out of range");
    ExpectIntRefused("99999999999999999999999", 2, 256, "out of range");
    ExpectIntRefused("1", 2, 256, "between 2 and 256");
    ExpectIntRefused("257", 2, 256, "between 2 and 256");
    ExpectIntRefused("-1", 0, 10, "out of range");
    ExpectIntRefused("2147483648", 0, std::numeric_limits<int>::max(), "out of range");
}

TEST(StrictParse, DoubleInRangeIsParsed)
{
    double value = 0;
    std::string error;
    EXPECT_TRUE(ParseDouble("0.25", 0, 1, value, error));
    EXPECT_EQ(value, 0.25);
    EXPECT_TRUE(ParseDouble("6e2", 1, kInfinity, value, error));
    EXPECT_EQ(value, 600.0);
    EXPECT_TRUE(ParseDouble(".5", 0, 1, value, error));
    EXPECT_EQ(value, 0.5);
    EXPECT_TRUE(ParseDouble("-3", -kInfinity, kInfinity, value, error));
    EXPECT_EQ(value, -3.0);
}

TEST(StrictParse, DoubleWithJunkOrNotFiniteIsRefused)
{
    for (const char *text : {"abc", "", " 1", "1 ", "0.5x", "nan", "inf", "-", "."})
        ExpectDoubleRefused(text, 0, 1, "expected a number between 0 and 1");
    ExpectDoubleRefused("1e999", 1, kInfinity, "out of range");
    ExpectDoubleRefused("-1e999", -kInfinity, kInfinity, "out of range");
    ExpectDoubleRefused("1.5", 0, 1, "out of range");
    ExpectDoubleRefused("0.5", 1, kInfinity, "a number of at least 1");
}

TEST(StrictParse, ChoiceMustMatchExactly)
{
    int index = -1;
    std::string error;
    EXPECT_TRUE(ParseChoice("icosahedron", {"octahedron", "icosahedron"}, index, error));
    EXPECT_EQ(index, 1);
    index = -1;
    for (const char *text : {"icosahedorn", "Icosahedron", "", "icosahedron "}) {
        EXPECT_FALSE(ParseChoice(text, {"octahedron", "icosahedron"}, index, error)) << text;
        EXPECT_EQ(index, -1);
        EXPECT_NE(error.find("expected one of octahedron|icosahedron"), std::string::npos) << error;
    }
}

TEST(StrictParse, MessagesQuoteBoundedPrintableText)
{
    EXPECT_EQ(Quoted("abc"), "'abc'");
    EXPECT_EQ(Quoted(std::string("a\0\n\x7f\xff", 5)), "'a\\x00\\x0a\\x7f\\xff'");
    EXPECT_EQ(Quoted(std::string(100, 'x')), "'" + std::string(40, 'x') + "...'");

    int value = 0;
    std::string error;
    EXPECT_FALSE(ParseInt(std::string(100000, '9') + "\n\x01", 0, 10, value, error));
    EXPECT_LT(error.size(), 120u) << error;
    for (char c : error) EXPECT_TRUE(c >= 0x20 && c < 0x7f) << error;
}
