/* Point and line loads from C: a simulation built in code with ps_sim_add_load() steps bit for
 * bit like the same scene read from JSON; bad loads are refused naming the problem, nothing
 * changed; the gravity ramp is a ps_sim_def field. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"

/* A 0.4 m × 0.1 m strip of 8 × 2 quads (27 vertices) clamped on its first two columns, a tip
 * force and a follower (normal) force spread by area and a couple about y on the last two
 * columns, ramped over two steps. */
static const char* const kLoadedStrip =
    "{ \"simulation\": { \"mode\": \"quasistatic\" },"
    "  \"effects\": [\"membrane\", \"bending\"],"
    "  \"bodies\": [ { \"name\": \"strip\", \"mesh\": { \"generator\": \"grid\", \"width\": 0.4,"
    "                  \"height\": 0.1, \"nx\": 8, \"ny\": 2 },"
    "                  \"material\": { \"youngs_modulus\": 1e9 } } ],"
    "  \"handles\": [ { \"body\": 0, \"vertices\": [0, 1, 9, 10, 18, 19] } ],"
    "  \"loads\": ["
    "    { \"body\": 0, \"vertices\": [8, 17, 26], \"force\": [0, 0, -0.002],"
    "      \"normal_force\": -0.001, \"distribution\": \"area\" },"
    "    { \"body\": 0, \"vertices\": [7, 8, 16, 17, 25, 26], \"distribution\": \"per_vertex\","
    "      \"moment\": { \"axis\": [0, 1, 0], \"magnitude\": 1e-4 }, \"ramp\": 0.02 } ] }";

static const int32_t kClamp[6] = {0, 1, 9, 10, 18, 19};
static const int32_t kTip[3] = {8, 17, 26};
static const int32_t kEnd[6] = {7, 8, 16, 17, 25, 26};

/* The strip of kLoadedStrip built in code on the JSON simulation's hierarchy. */
static ps_sim* strip_in_code(const ps_hierarchy* h) {
  ps_sim_def def;
  ps_sim_def_init(&def);
  def.mode = PS_MODE_QUASISTATIC;
  def.effects = PS_EFFECT_MEMBRANE | PS_EFFECT_BENDING;
  def.pinned_vertices = kClamp;
  def.num_pinned_vertices = 6;
  def.material_youngs_modulus = 1e9;
  ps_sim* sim = NULL;
  CHECK(ps_sim_create(h, &def, &sim) == PS_OK);
  ps_load_def tip;
  ps_load_def_init(&tip);
  tip.vertices = kTip;
  tip.num_vertices = 3;
  tip.force[2] = -0.002;
  tip.normal_force = -0.001;
  tip.distribution = PS_LOAD_BY_AREA;
  int32_t index = -1;
  CHECK(ps_sim_add_load(sim, &tip, &index) == PS_OK && index == 0);
  ps_load_def couple;
  ps_load_def_init(&couple);
  couple.vertices = kEnd;
  couple.num_vertices = 6;
  couple.distribution = PS_LOAD_PER_VERTEX;
  couple.moment_axis[1] = 1.0;
  couple.moment_axis[2] = 0.0;
  couple.moment = 1e-4;
  couple.ramp = 0.02;
  CHECK(ps_sim_add_load(sim, &couple, &index) == PS_OK && index == 1);
  return sim;
}

static void test_code_equals_json(void) {
  ps_sim* from_json = NULL;
  CHECK(ps_sim_create_from_scene(kLoadedStrip, NULL, &from_json) == PS_OK);
  const ps_hierarchy* h = NULL;
  CHECK(ps_sim_hierarchy(from_json, &h) == PS_OK);
  ps_sim* from_code = strip_in_code(h);
  int32_t loads = 0;
  CHECK(ps_sim_num_loads(from_json, &loads) == PS_OK && loads == 2);
  CHECK(ps_sim_num_loads(from_code, &loads) == PS_OK && loads == 2);
  double a[81], b[81];
  size_t count = 0;
  for (int step = 0; step < 3; ++step) {
    CHECK(ps_sim_step_preview(from_json, 1) == PS_OK);
    CHECK(ps_sim_step_preview(from_code, 1) == PS_OK);
    CHECK(ps_sim_get_positions(from_json, 0, a, 81, &count) == PS_OK && count == 81);
    CHECK(ps_sim_get_positions(from_code, 0, b, 81, &count) == PS_OK && count == 81);
    CHECK(memcmp(a, b, sizeof a) == 0); /* bit for bit */
  }
  CHECK(a[3 * 26 + 2] < -1e-4); /* the tip force pulls the tip down */
  ps_sim_destroy(from_code);
  ps_sim_destroy(from_json);
}

static void test_bad_loads(void) {
  ps_sim* sim = NULL;
  CHECK(ps_sim_create_from_scene(kLoadedStrip, NULL, &sim) == PS_OK);
  ps_load_def def;
  memset(&def, 0, sizeof def);
  CHECK_ERROR(ps_sim_add_load(sim, &def, NULL), PS_ERROR_UNINITIALIZED_DEF, ps_sim_last_error(sim),
              "ps_load_def");
  CHECK_ERROR(ps_sim_add_load(sim, NULL, NULL), PS_ERROR_NULL_ARGUMENT, ps_sim_last_error(sim),
              "def");
  ps_load_def_init(&def);
  CHECK_ERROR(ps_sim_add_load(sim, &def, NULL), PS_ERROR_INVALID_SCENE, ps_sim_last_error(sim),
              "loads[2]: selects no vertices");
  def.vertices = kTip;
  def.num_vertices = 3;
  def.force[1] = NAN;
  CHECK_ERROR(ps_sim_add_load(sim, &def, NULL), PS_ERROR_INVALID_SCENE, ps_sim_last_error(sim),
              "loads[2].force has a non-finite value");
  def.force[1] = 1.0;
  def.ramp = -1.0;
  CHECK_ERROR(ps_sim_add_load(sim, &def, NULL), PS_ERROR_INVALID_SCENE, ps_sim_last_error(sim),
              "loads[2].ramp");
  def.ramp = 0.0;
  def.distribution = (ps_load_distribution)7;
  CHECK_ERROR(ps_sim_add_load(sim, &def, NULL), PS_ERROR_INVALID_ARGUMENT, ps_sim_last_error(sim),
              "ps_load_distribution");
  def.distribution = PS_LOAD_BY_MASS;
  const int32_t outside[1] = {27};
  def.vertices = outside;
  def.num_vertices = 1;
  CHECK_ERROR(ps_sim_add_load(sim, &def, NULL), PS_ERROR_INVALID_SCENE, ps_sim_last_error(sim),
              "vertex 27 is out of range");
  def.vertices = kTip;
  def.num_vertices = 3;
  def.moment = 1.0;
  def.moment_axis[0] = 0.0;
  def.moment_axis[1] = 1.0;
  def.moment_axis[2] = 0.0; /* the tip edge lies along y: it cannot carry a twist about y */
  CHECK_ERROR(ps_sim_add_load(sim, &def, NULL), PS_ERROR_INVALID_SCENE, ps_sim_last_error(sim),
              "loads[2].moment");
  int32_t loads = 0;
  CHECK(ps_sim_num_loads(sim, &loads) == PS_OK && loads == 2); /* nothing changed */
  CHECK(ps_sim_step_preview(sim, 1) == PS_OK);
  ps_sim_destroy(sim);
}

static void test_gravity_ramp(void) {
  ps_sim* json = NULL;
  CHECK(ps_sim_create_from_scene(kLoadedStrip, NULL, &json) == PS_OK);
  const ps_hierarchy* h = NULL;
  CHECK(ps_sim_hierarchy(json, &h) == PS_OK);
  ps_sim_def def;
  ps_sim_def_init(&def);
  CHECK(def.simulation_gravity_ramp == 0.0);
  def.simulation_gravity_ramp = 0.5;
  ps_sim* sim = NULL;
  CHECK(ps_sim_create(h, &def, &sim) == PS_OK);
  double value = 0.0;
  CHECK(ps_sim_get_param(sim, "simulation.gravity_ramp", &value) == PS_OK && value == 0.5);
  CHECK_ERROR(ps_sim_set_param(sim, "simulation.gravity_ramp", -1.0), PS_ERROR_INVALID_ARGUMENT,
              ps_sim_last_error(sim), "gravity_ramp");
  ps_sim_destroy(sim);
  ps_sim_destroy(json);
}

int main(void) {
  test_code_equals_json();
  test_bad_loads();
  test_gravity_ramp();
  if (failures) fprintf(stderr, "%d check(s) failed\n", failures);
  return failures ? 1 : 0;
}
