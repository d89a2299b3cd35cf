// series.csv across program versions: a run that an older orodem started
// (fewer columns) is continued with the columns it has, row for row; any
// other header is refused with both headers named.
#include <gtest/gtest.h>

#include <string>

#include "orodem/core/error.hpp"
#include "orodem/io/series_reader.hpp"

using namespace orodem;

TEST(SeriesCsv, AnOlderRunKeepsItsLeadingColumns) {
    const std::string now = "step,time,S,base_normal_force,trailing_wall_push";
    EXPECT_EQ(csv_leading_columns(now, now, "series.csv"), 5u);
    EXPECT_EQ(csv_leading_columns("step,time,S,base_normal_force", now, "series.csv"), 4u);
    EXPECT_EQ(csv_leading_columns("step", now, "series.csv"), 1u);
    // The new row cut to the old columns lines up with the old header.
    const std::string row = "100,1.5,0.25,-3.2e+08,1.4e+07";
    EXPECT_EQ(csv_first_fields(row, 4), "100,1.5,0.25,-3.2e+08");
    EXPECT_EQ(csv_first_fields(row, 5), row);
    EXPECT_EQ(csv_first_fields(row, 99), row);
    EXPECT_EQ(csv_first_fields(row, 1), "100");
    EXPECT_EQ(csv_first_fields(row, 0), "");
}

TEST(SeriesCsv, AnyOtherHeaderIsRefusedNamingBoth) {
    const std::string now = "step,time,S,base_normal_force";
    for (const std::string bad : {"step,time,X", "step,tim", "", "step,time,S,base_normal_force,extra", "time,step"}) {
        try {
            csv_leading_columns(bad, now, "runs/a/series.csv");
            ADD_FAILURE() << "accepted '" << bad << "'";
        } catch (const ConfigError& e) {
            const std::string m = e.what();
            EXPECT_NE(m.find("'runs/a/series.csv' has the columns '" + bad + "'"), std::string::npos) << m;
            EXPECT_NE(m.find("'" + now + "'"), std::string::npos) << m;
        }
    }
}
