/* Handles, obstacles and the ground from C: a scene built in code with ps_sim_add_handle(),
 * ps_sim_add_obstacle(), their keyframed and constant motions and ps_sim_set_ground() steps bit
 * for bit like the same scene read from JSON; bad objects are refused naming the problem, with
 * nothing changed. argv[1]: the directory of tests/data (the JSON scene's obstacle file). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"

/* A 0.4 m square sheet of 4 × 4 quads (vertex (i, j) at 5 j + i) falling in −z onto a plate
 * (tests/data/plate.obj) that rises 1 cm in 0.1 s; two corners lifted 2 cm by smooth keys, a
 * third corner rising at 0.1 m/s; a frictional ground 10 cm below. */
static const char* const kScene =
    "{ \"simulation\": { \"time_step\": 0.01 }, \"gravity\": [0, 0, -9.81],"
    "  \"effects\": [\"membrane\", \"bending\", \"gravity\", \"contact\", \"friction\"],"
    "  \"bodies\": [ { \"name\": \"sheet\", \"mesh\": { \"generator\": \"grid\", \"width\": 0.4,"
    "                  \"height\": 0.4, \"nx\": 4, \"ny\": 4 } } ],"
    "  \"handles\": ["
    "    { \"body\": 0, \"vertices\": [0, 4], \"motion\": { \"interpolation\": \"smooth\","
    "      \"keyframes\": [ {\"time\": 0}, {\"time\": 0.1, \"translation\": [0, 0, 0.02]} ] } },"
    "    { \"body\": 0, \"vertices\": [24], \"motion\": { \"velocity\": [0, 0, 0.1] } } ],"
    "  \"obstacles\": [ { \"mesh\": { \"file\": \"plate.obj\" }, \"friction\": 0.2,"
    "      \"motion\": { \"keyframes\": [ {\"time\": 0},"
    "                                   {\"time\": 0.1, \"translation\": [0, 0, 0.01]} ] } } ],"
    "  \"ground\": { \"normal\": [0, 0, 2], \"height\": -0.1, \"friction\": 0.3 } }";

static const double kPlate[12] = {0.1, 0.1, -0.03, 0.3, 0.1, -0.03,
                                  0.3, 0.3, -0.03, 0.1, 0.3, -0.03};
static const int32_t kPlateFaces[6] = {0, 1, 2, 0, 2, 3};
static const int32_t kLifted[2] = {0, 4};
static const int32_t kRising[1] = {24};

static const uint32_t kEffects = PS_EFFECT_MEMBRANE | PS_EFFECT_BENDING | PS_EFFECT_GRAVITY |
                                 PS_EFFECT_CONTACT | PS_EFFECT_FRICTION;

/* A simulation of the sheet alone on h: no handle, obstacle or ground yet. */
static ps_sim* bare_sheet(const ps_hierarchy* h) {
  ps_sim_def def;
  ps_sim_def_init(&def);
  def.effects = kEffects;
  def.gravity[1] = 0.0;
  def.gravity[2] = -9.81;
  ps_sim* sim = NULL;
  CHECK(ps_sim_create(h, &def, &sim) == PS_OK);
  return sim;
}

static ps_obstacle_def plate_def(void) {
  ps_obstacle_def def;
  ps_obstacle_def_init(&def);
  def.vertices = kPlate;
  def.num_vertices = 4;
  def.faces = kPlateFaces;
  def.num_faces = 2;
  def.friction = 0.2;
  return def;
}

/* kScene built in code on the JSON simulation's hierarchy. */
static ps_sim* scene_in_code(const ps_hierarchy* h) {
  ps_sim* sim = bare_sheet(h);
  int32_t index = -1;
  CHECK(ps_sim_add_handle(sim, 0, kLifted, 2, &index) == PS_OK && index == 0);
  const double lift[16] = {0, 0, 0, 0, 0, 0, 1, 0, 0.1, 0, 0, 0.02, 0, 0, 1, 0};
  CHECK(ps_sim_set_handle_keyframes(sim, 0, lift, 2, PS_INTERPOLATION_SMOOTH) == PS_OK);
  CHECK(ps_sim_add_handle(sim, 0, kRising, 1, &index) == PS_OK && index == 1);
  const double up[3] = {0, 0, 0.1};
  CHECK(ps_sim_set_handle_motion(sim, 1, up, NULL, NULL, 0.0, NULL) == PS_OK);
  const ps_obstacle_def plate = plate_def();
  CHECK(ps_sim_add_obstacle(sim, &plate, &index) == PS_OK && index == 0);
  const double rise[16] = {0, 0, 0, 0, 0, 0, 1, 0, 0.1, 0, 0, 0.01, 0, 0, 1, 0};
  CHECK(ps_sim_set_obstacle_keyframes(sim, 0, rise, 2, PS_INTERPOLATION_LINEAR) == PS_OK);
  const double normal[3] = {0, 0, 2};
  CHECK(ps_sim_set_ground(sim, 1, normal, -0.1, 0.3) == PS_OK);
  return sim;
}

static void test_code_equals_json(const char* data_dir) {
  ps_sim* from_json = NULL;
  CHECK(ps_sim_create_from_scene(kScene, data_dir, &from_json) == PS_OK);
  const ps_hierarchy* h = NULL;
  CHECK(ps_sim_hierarchy(from_json, &h) == PS_OK);
  ps_sim* from_code = scene_in_code(h);
  int32_t n = 0;
  CHECK(ps_sim_num_handles(from_code, &n) == PS_OK && n == 2);
  CHECK(ps_sim_num_obstacles(from_code, &n) == PS_OK && n == 1);
  CHECK(ps_sim_num_obstacles(from_json, &n) == PS_OK && n == 1);
  double a[75], b[75];
  size_t count = 0;
  for (int step = 0; step < 15; ++step) {
    CHECK(ps_sim_step_preview(from_json, 1) == PS_OK);
    CHECK(ps_sim_step_preview(from_code, 1) == PS_OK);
    CHECK(ps_sim_get_positions(from_json, 0, a, 75, &count) == PS_OK && count == 75);
    CHECK(ps_sim_get_positions(from_code, 0, b, 75, &count) == PS_OK && count == 75);
    CHECK(memcmp(a, b, sizeof a) == 0); /* bit for bit */
  }
  /* The keys and the velocity moved the handles exactly; the plate (at −0.02 m after 0.1 s)
   * holds the sheet's centre up, where free fall for 0.15 s would have taken it to −0.11 m. */
  CHECK(a[2] == 0.02 && a[3 * 4 + 2] == 0.02);
  CHECK(fabs(a[3 * 24 + 2] - 0.015) < 1e-12);
  CHECK(a[3 * 12 + 2] > -0.02 && a[3 * 12 + 2] < 0.0);
  ps_sim_destroy(from_code);
  ps_sim_destroy(from_json);
}

static void test_bad_objects(const char* data_dir) {
  ps_sim* json = NULL;
  CHECK(ps_sim_create_from_scene(kScene, data_dir, &json) == PS_OK);
  const ps_hierarchy* h = NULL;
  CHECK(ps_sim_hierarchy(json, &h) == PS_OK);
  ps_sim* sim = bare_sheet(h);
  ps_obstacle_def def;
  memset(&def, 0, sizeof def);
  CHECK_ERROR(ps_sim_add_obstacle(sim, &def, NULL), PS_ERROR_UNINITIALIZED_DEF,
              ps_sim_last_error(sim), "ps_obstacle_def");
  ps_obstacle_def_init(&def);
  CHECK_ERROR(ps_sim_add_obstacle(sim, &def, NULL), PS_ERROR_NULL_ARGUMENT, ps_sim_last_error(sim),
              "vertices");
  def = plate_def();
  const double nan_plate[12] = {0.1, 0.1, NAN, 0.3, 0.1, -0.03, 0.3, 0.3, -0.03, 0.1, 0.3, -0.03};
  def.vertices = nan_plate;
  CHECK_ERROR(ps_sim_add_obstacle(sim, &def, NULL), PS_ERROR_INVALID_MESH, ps_sim_last_error(sim),
              "obstacles[0]");
  def = plate_def();
  const int32_t outside[6] = {0, 1, 2, 0, 2, 4};
  def.faces = outside;
  CHECK_ERROR(ps_sim_add_obstacle(sim, &def, NULL), PS_ERROR_INVALID_MESH, ps_sim_last_error(sim),
              "obstacles[0]");
  /* A vertical triangle through the sheet's centre (0.2, 0.2, 0): refused before any step. */
  const double spike[9] = {0.15, 0.2, -0.05, 0.25, 0.2, -0.05, 0.2, 0.2, 0.05};
  const int32_t spike_face[3] = {0, 1, 2};
  def = plate_def();
  def.vertices = spike;
  def.num_vertices = 3;
  def.faces = spike_face;
  def.num_faces = 1;
  CHECK_ERROR(ps_sim_add_obstacle(sim, &def, NULL), PS_ERROR_INTERSECTING, ps_sim_last_error(sim),
              "obstacle face 0 cross");
  def = plate_def();
  def.friction = -1.0;
  CHECK_ERROR(ps_sim_add_obstacle(sim, &def, NULL), PS_ERROR_INVALID_SCENE, ps_sim_last_error(sim),
              "friction");
  CHECK_ERROR(ps_sim_set_obstacle_motion(sim, 0, NULL, NULL, NULL, 0.0, NULL),
              PS_ERROR_OUT_OF_RANGE, ps_sim_last_error(sim), "obstacle 0 does not exist");
  const int32_t far[1] = {25};
  CHECK_ERROR(ps_sim_add_handle(sim, 0, far, 1, NULL), PS_ERROR_INVALID_SCENE,
              ps_sim_last_error(sim), "handles[0]: vertex 25 is out of range");
  CHECK_ERROR(ps_sim_add_handle(sim, 1, kRising, 1, NULL), PS_ERROR_INVALID_SCENE,
              ps_sim_last_error(sim), "body index 1 does not exist");
  CHECK_ERROR(ps_sim_add_handle(sim, 0, kRising, 0, NULL), PS_ERROR_INVALID_SCENE,
              ps_sim_last_error(sim), "selects no vertices");
  const double zero[3] = {0, 0, 0};
  CHECK_ERROR(ps_sim_set_ground(sim, 1, zero, 0.0, 0.0), PS_ERROR_INVALID_ARGUMENT,
              ps_sim_last_error(sim), "ground: normal");
  const double up[3] = {0, 0, 1};
  CHECK_ERROR(ps_sim_set_ground(sim, 1, up, 0.1, 0.0), PS_ERROR_INTERSECTING,
              ps_sim_last_error(sim), "ground");
  int32_t n = -1;
  CHECK(ps_sim_num_obstacles(sim, &n) == PS_OK && n == 0); /* nothing changed */
  CHECK(ps_sim_num_handles(sim, &n) == PS_OK && n == 0);

  const ps_obstacle_def plate = plate_def();
  CHECK(ps_sim_add_obstacle(sim, &plate, NULL) == PS_OK);
  const double unordered[16] = {0.1, 0, 0, 0, 0, 0, 1, 0, 0.05, 0, 0, 0.01, 0, 0, 1, 0};
  CHECK_ERROR(ps_sim_set_obstacle_keyframes(sim, 0, unordered, 2, PS_INTERPOLATION_LINEAR),
              PS_ERROR_INVALID_ARGUMENT, ps_sim_last_error(sim),
              "obstacles[0].motion.keyframes[1].time");
  CHECK(ps_sim_step_preview(sim, 1) == PS_OK);
  CHECK_ERROR(ps_sim_add_handle(sim, 0, kRising, 1, NULL), PS_ERROR_WRONG_CALL_ORDER,
              ps_sim_last_error(sim), "before the first step");
  CHECK_ERROR(ps_sim_add_obstacle(sim, &plate, NULL), PS_ERROR_WRONG_CALL_ORDER,
              ps_sim_last_error(sim), "before the first step");
  CHECK(ps_sim_set_ground(sim, 1, up, -0.5, 0.0) == PS_OK); /* between steps: allowed */
  CHECK(ps_sim_step_preview(sim, 1) == PS_OK);
  ps_sim_destroy(sim);

  ps_sim_def no_contact;
  ps_sim_def_init(&no_contact);
  CHECK(ps_sim_create(h, &no_contact, &sim) == PS_OK);
  CHECK_ERROR(ps_sim_add_obstacle(sim, &plate, NULL), PS_ERROR_INVALID_SCENE,
              ps_sim_last_error(sim), "'contact'");
  CHECK_ERROR(ps_sim_set_ground(sim, 1, NULL, -0.5, 0.0), PS_ERROR_INVALID_SCENE,
              ps_sim_last_error(sim), "'contact'");
  ps_sim_destroy(sim);
  ps_sim_destroy(json);
}

int main(int argc, char** argv) {
  if (argc < 2) {
    fprintf(stderr, "usage: %s <tests/data directory>\n", argv[0]);
    return 2;
  }
  test_code_equals_json(argv[1]);
  test_bad_objects(argv[1]);
  if (failures) fprintf(stderr, "%d check(s) failed\n", failures);
  return failures ? 1 : 0;
}
