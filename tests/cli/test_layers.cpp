// Layered wedges with the real binary ([materials.NAME], [[layers]]; docs
// physics.md "Materials, layers and weakening"): a layered config whose one
// material is [material] gives the bytes of the one-material run (the per-pair
// kernel and the layer bookkeeping change nothing else); an interrupted
// weakening, cohesion-losing layered run resumes to the bytes of an
// uninterrupted one at another thread count; the snapshots carry material,
// layer and damage, the layers are where the config puts them and damage
// grows where the wedge shears; every config error is one line, exit 2,
// nothing written.
#include <gtest/gtest.h>

#include <signal.h>

#include <filesystem>
#include <string>

#include "cli/checkpoint_util.hpp"
#include "cli/cli_util.hpp"

namespace fs = std::filesystem;
using namespace cli;

namespace {

class Layers : public OrodemTest {
protected:
    /// The tiny exp1 of cli_util.hpp plus `extra` TOML.
    fs::path config(const std::string& name, const std::string& extra) {
        write_tiny_exp1(work_, name);
        const fs::path p = work_ / name;
        write(p, slurp(p) + extra);
        return p;
    }
};

const std::string kOneMaterialInTwoLayers =
    "[materials.same]\n"
    "[[layers]]\nmaterial = \"same\"\nthickness = 0.3\n"
    "[[layers]]\nmaterial = \"same\"\nthickness = 0.7\n";

const std::string kWeakBaseAndWeakeningCover =
    "[materials.weak]\nmu = 0.1\n"
    "[materials.sand]\nmu = 0.6\nmu_residual = 0.3\nweakening_distance = 0.2\ncohesion = 5000.0\ncohesion_loss = true\n"
    "[[layers]]\nmaterial = \"weak\"\nthickness = 0.25\n"
    "[[layers]]\nmaterial = \"sand\"\nthickness = 0.75\n";

}  // namespace

TEST_F(Layers, OneMaterialInTwoLayersGivesTheBytesOfTheOneMaterialRun) {
    const fs::path plain = config("plain.toml", ""), layered = config("layered.toml", kOneMaterialInTwoLayers);
    ASSERT_EQ(orodem("run " + quote(plain.string()) + " --out A --threads 1").status, 0);
    const Result r = orodem("run " + quote(layered.string()) + " --out B --threads 2");
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(slurp(work_ / "A" / "series.csv"), slurp(work_ / "B" / "series.csv"));
    EXPECT_EQ(slurp(work_ / "A" / "faults.csv"), slurp(work_ / "B" / "faults.csv"));
    // The resolved config names the layers and reads back (a resume loads it).
    const std::string resolved = slurp(work_ / "B" / "config.toml");
    EXPECT_NE(resolved.find("[[layers]]\nmaterial = 'same'\nthickness = 0.3\n"), std::string::npos) << resolved;
    EXPECT_EQ(orodem("check " + quote((work_ / "B" / "config.toml").string())).status, 0);
    // --color-by damage draws a layered run and refuses a one-material one (exit 2, nothing written).
    EXPECT_EQ(orodem("render B --color-by damage --out damage.png").status, 0);
    EXPECT_TRUE(fs::exists(work_ / "damage.png"));
    const Result plain_damage = orodem("render A --color-by damage --out plain.png");
    EXPECT_EQ(plain_damage.status, 2);
    EXPECT_NE(plain_damage.err.find("holds no damage array: only a layered run"), std::string::npos) << plain_damage.err;
    EXPECT_FALSE(fs::exists(work_ / "plain.png"));
}

TEST_F(Layers, AnInterruptedWeakeningRunResumesToTheBytesOfAnUninterruptedOne) {
    const fs::path cfg = config("weak.toml", kWeakBaseAndWeakeningCover);
    // Outputs every 0.1 (expect_same_outputs compares more than five pictures).
    ASSERT_EQ(orodem("run " + quote(cfg.string()) + " --out A --threads 1 --set wedge.output_ds=0.1").status, 0);
    const fs::path run = work_ / "B";
    const Proc p = start({"run", cfg.string(), "--out", run.string(), "--threads", "1", "--set", "wedge.output_ds=0.1"},
                         root_ / "B");
    ASSERT_TRUE(signal_after_checkpoint(p, run, {SIGTERM})) << slurp(p.err);
    ASSERT_EQ(wait_for(p), 143) << slurp(p.err);
    ASSERT_LT(slurp(run / "series.csv").size(), slurp(work_ / "A" / "series.csv").size()) << "was not interrupted";
    const Result r = orodem("run " + quote((run / "config.toml").string()) + " --out B --resume --threads 2");
    ASSERT_EQ(r.status, 0) << r.err;
    expect_same_outputs(work_ / "A", run);
}

TEST_F(Layers, SnapshotsCarryMaterialLayerAndDamageWhereTheConfigPutsThem) {
    const fs::path cfg = config("weak.toml", kWeakBaseAndWeakeningCover);
    ASSERT_EQ(orodem("run " + quote(cfg.string()) + " --out A --threads 2").status, 0);
    // The Python reader's view of the last snapshot: each particle (a
    // cluster's discs together, by their mean height at the cut, h0 minus
    // initial_depth) is in the weak material (id 1 in name order: sand 0,
    // weak 1) and layer 0 (on either side) below 0.25 h0, else sand and
    // layer 1; the damage of the resting retroside beyond 1.5 h0 (the
    // contacts' first settling only, about 0.05 d̄) is far below that where
    // the layer shears (more than a mean diameter of sliding).
    const std::string py =
        "import sys, numpy as np; sys.path.insert(0, " + quote(std::string(ORODEM_SOURCE_DIR) + "/python") +
        ")\nimport orodem\nr = orodem.open_run('A')\ns = r.snapshot(r.outputs[-1])\n"
        "h0 = r.config['packing']['h0']\nheight = h0 - s['initial_depth']\ncl = s['cluster_id']\n"
        "for c in np.unique(cl[cl >= 0]):\n    height[cl == c] = np.mean(height[cl == c])\n"
        "weak = height < 0.25 * h0\n"
        "one_side = np.ones(len(cl), bool)\n"
        "for c in np.unique(cl[cl >= 0]):\n    one_side[cl == c] = len(set(s['side'][cl == c].tolist())) == 1\n"
        "want = np.where(weak, 0, 1)\n"
        "print('material_ok', np.mean(s['material'] == np.where(weak, 1, 0)),"
        " 'layer_ok', np.mean((s['layer'] == want)[one_side]))\n"
        "d = s['damage']\nprint('resting', np.median(d[s['x'] > 1.5 * h0]), 'max', d.max())\n";
    write(work_ / "check.py", py);
    std::string out;
    ASSERT_EQ(run("cd " + quote(work_.string()) + " && /usr/bin/python3 check.py", &out), 0) << out;
    std::istringstream in(out);
    std::string w;
    double material_ok = 0, layer_ok = 0, resting = 1, dmax = 0;
    in >> w >> material_ok >> w >> layer_ok >> w >> resting >> w >> dmax;
    EXPECT_GT(material_ok, 0.999) << out;  // h0 - (h0 - y) may round across a band edge: one particle in a thousand
    EXPECT_GT(layer_ok, 0.999) << out;     // (clusters straddling the S point, whose side is their centre's, left out)
    EXPECT_GT(dmax, 1.0) << out;
    EXPECT_LT(resting, 0.2) << out;
    EXPECT_GT(resting, 0.0) << out;
}

TEST_F(Layers, TheBiaxialTestOfANamedMaterialWithoutWeakeningIsThatOfMaterial) {
    // calibrate.material = a material equal to [material] (μ 0.5, no
    // weakening): the per-pair law gives the bytes of the one-law test.
    const std::string common = "[run]\nexperiment = \"biaxial\"\n[calibrate]\nkinds = [\"clusters\"]\nwidth = 16.0\n"
                               "height = 32.0\nmax_strain = 0.02\ncritical_from = 0.01\noutput_strain = 0.0025\n"
                               "compaction_mu = 0.0\n";
    write(work_ / "plain.toml", common + "mu_values = [0.5]\n");
    write(work_ / "named.toml", common + "material = \"grit\"\n[materials.grit]\nmu = 0.5\n");
    ASSERT_EQ(orodem("calibrate plain.toml --out A --threads 1").status, 0);
    const Result r = orodem("calibrate named.toml --out B --threads 2");
    ASSERT_EQ(r.status, 0) << r.err;
    const std::string a = slurp(work_ / "A" / "biaxial-clusters-mu0.5.csv");
    EXPECT_GT(a.size(), 100u);
    EXPECT_EQ(a, slurp(work_ / "B" / "biaxial-clusters-mu0.5.csv"));
    // A weakening material weakens: the peak is lower.
    write(work_ / "weak.toml", common + "material = \"grit\"\n[materials.grit]\nmu = 0.5\nmu_residual = 0.1\n"
                                        "weakening_distance = 0.01\n");
    ASSERT_EQ(orodem("calibrate weak.toml --out C --threads 1").status, 0);
    EXPECT_NE(a, slurp(work_ / "C" / "biaxial-clusters-mu0.5.csv"));
    const Result bad = orodem("calibrate named.toml --out D --set calibrate.material='\"clay\"'");
    EXPECT_EQ(bad.status, 2);
    EXPECT_NE(bad.err.find("key 'calibrate.material' = \"clay\": no [materials.clay]"), std::string::npos) << bad.err;
    EXPECT_FALSE(fs::exists(work_ / "D"));
}

TEST_F(Layers, TheBasalFrictionOfALayeredBlock) {
    // [[layers]] in the basal-friction block, in fractions of its height:
    // one material equal to [material] gives the one-law bytes, and a weak
    // basal layer (μ_i 0.1 under 0.3) runs and changes the result.
    const std::string common = "[run]\nexperiment = \"basal-friction\"\n[calibrate]\nkinds = [\"clusters\"]\n"
                               "mu_bp_values = [0.5]\nblock_length = 12.0\nblock_height = 6.0\nduration = 20.0\n";
    write(work_ / "plain.toml", common);
    write(work_ / "one.toml", common + "[materials.same]\n[[layers]]\nmaterial = \"same\"\nthickness = 1.0\n");
    write(work_ / "weak.toml", common + "[materials.weak]\nmu = 0.1\n[materials.cover]\n"
                                        "[[layers]]\nmaterial = \"weak\"\nthickness = 0.2\n"
                                        "[[layers]]\nmaterial = \"cover\"\nthickness = 0.8\n");
    ASSERT_EQ(orodem("calibrate plain.toml --out A --threads 1").status, 0);
    const Result one = orodem("calibrate one.toml --out B --threads 2");
    ASSERT_EQ(one.status, 0) << one.err;
    const Result weak = orodem("calibrate weak.toml --out C --threads 2");
    ASSERT_EQ(weak.status, 0) << weak.err;
    const std::string f = "basal-friction-clusters-mu_bp0.5.csv";
    EXPECT_GT(slurp(work_ / "A" / f).size(), 100u);
    EXPECT_EQ(slurp(work_ / "A" / f), slurp(work_ / "B" / f));
    EXPECT_NE(slurp(work_ / "A" / f), slurp(work_ / "C" / f));
}

TEST_F(Layers, ConfigErrorsAreOneLineExit2AndWriteNothing) {
    struct Case {
        std::string extra, says;
    } cases[] = {
        {"[materials.sand]\n[[layers]]\nmaterial = \"salt\"\nthickness = 1.0\n",
         "key 'layers[0].material' = \"salt\": no [materials.salt]; the materials are: sand"},
        {"[materials.sand]\n[[layers]]\nmaterial = \"sand\"\nthickness = 0.5\n",
         "[[layers]]: the thicknesses add up to 0.5 h0; they must add up to 1"},
        {"[materials.sand]\nmu = 0.4\nmu_residual = 0.5\n[[layers]]\nmaterial = \"sand\"\nthickness = 1.0\n",
         "key 'materials.sand.mu_residual' = 0.5: must be at most materials.sand.mu = 0.4"},
        {"[materials.sand]\nfriction = 0.4\n[[layers]]\nmaterial = \"sand\"\nthickness = 1.0\n",
         "unknown key 'materials.sand.friction'"},
        {"[materials.sand]\n", "[materials] are used through [[layers]]"},
        {"[[layers]]\nmaterial = \"sand\"\nthickness = 1.0\n", "a layered wedge needs its materials"},
        {"[materials.sand]\n[[layers]]\nmaterial = \"sand\"\nthickness = 1.0\n"
         "[[friction_pairs]]\na = \"sand\"\nb = \"clay\"\nmu = 0.2\n",
         "key 'friction_pairs[0].b' = \"clay\": no [materials.clay]"},
        {"[materials.sand]\nk_s_over_k_n = 0.0\n[[layers]]\nmaterial = \"sand\"\nthickness = 1.0\n",
         "key 'materials.sand.k_s_over_k_n' = 0: must be a number in (0, 10]"},
    };
    int k = 0;
    for (const Case& c : cases) {
        const fs::path cfg = config("bad" + std::to_string(k) + ".toml", c.extra);
        const std::string out = "out" + std::to_string(k++);
        const Result r = orodem("run " + quote(cfg.string()) + " --out " + out);
        EXPECT_EQ(r.status, 2) << c.extra << r.err;
        EXPECT_NE(r.err.find(c.says), std::string::npos) << r.err;
        EXPECT_EQ(count_lines(r.err), 1) << r.err;
        EXPECT_FALSE(fs::exists(work_ / out)) << c.extra;
    }
}
