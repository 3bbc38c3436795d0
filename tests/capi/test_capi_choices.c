/* Named options from C (the choice table): listed with their values, set by name on a
 * simulation built in code, which then steps bit for bit like the same scene read from JSON,
 * also on a PSQ hierarchy where they change how the driver is built; unknown names and values
 * are refused listing the known ones. */
#include <stdlib.h>
#include <string.h>

#include "check.h"

/* A 0.4 m square sheet of 4 × 4 quads clamped on its first two rows, sagging under gravity in load
 * steps on two levels, with every progressive option off its default and mid-edge bending. */
static const char* const kScene =
    "{ \"simulation\": { \"mode\": \"quasistatic\" }, \"gravity\": [0, 0, -9.81],"
    "  \"effects\": [\"membrane\", \"bending\", \"gravity\"],"
    "  \"bodies\": [ { \"mesh\": { \"generator\": \"grid\", \"width\": 0.4, \"height\": 0.4,"
    "                  \"nx\": 4, \"ny\": 4 }, \"material\": { \"bending_model\": \"midedge\" } } "
    "],"
    "  \"handles\": [ { \"body\": 0, \"vertices\": [0, 1, 2, 3, 4, 5, 6, 7, 8, 9] } ],"
    "  \"progressive\": { \"levels\": [12], \"proxy_hessian\": \"galerkin\","
    "                     \"prolongation\": \"direct\", \"preview_membrane\": \"tension_field\" } "
    "}";

static const int32_t kClamp[10] = {0, 1, 2, 3, 4, 5, 6, 7, 8, 9};

static void test_the_table_is_listed(void) {
  CHECK(ps_choice_count() == 7);
  ps_choice_info info;
  CHECK(ps_choice_info_get(0, &info) == PS_OK);
  CHECK(strcmp(info.name, "simulation.mode") == 0);
  CHECK(strcmp(info.options, "dynamic|quasistatic") == 0);
  CHECK(strcmp(info.default_option, "dynamic") == 0 && strlen(info.doc) > 20);
  int found = 0;
  for (int32_t k = 0; k < ps_choice_count(); ++k) {
    CHECK(ps_choice_info_get(k, &info) == PS_OK);
    found += strcmp(info.name, "progressive.proxy_hessian") == 0 &&
             strcmp(info.options, "auto|level|galerkin") == 0;
  }
  CHECK(found == 1);
  CHECK_ERROR(ps_choice_info_get(7, &info), PS_ERROR_OUT_OF_RANGE, ps_last_error(), "0 to 6");
  CHECK_ERROR(ps_choice_info_get(0, NULL), PS_ERROR_NULL_ARGUMENT, ps_last_error(), "out");
}

static void test_code_equals_json_on_two_levels(void) {
  ps_sim* from_json = NULL;
  CHECK(ps_sim_create_from_scene(kScene, NULL, &from_json) == PS_OK);
  const ps_hierarchy* h = NULL;
  CHECK(ps_sim_hierarchy(from_json, &h) == PS_OK);
  ps_sim_def def;
  ps_sim_def_init(&def);
  def.mode = PS_MODE_QUASISTATIC;
  def.gravity[1] = 0.0;
  def.gravity[2] = -9.81;
  def.pinned_vertices = kClamp;
  def.num_pinned_vertices = 10;
  ps_sim* sim = NULL;
  CHECK(ps_sim_create(h, &def, &sim) == PS_OK);
  CHECK(ps_sim_set_choice(sim, "material.bending_model", "midedge") == PS_OK);
  CHECK(ps_sim_set_choice(sim, "progressive.proxy_hessian", "galerkin") == PS_OK);
  CHECK(ps_sim_set_choice(sim, "progressive.prolongation", "direct") == PS_OK);
  CHECK(ps_sim_set_choice(sim, "progressive.preview_membrane", "tension_field") == PS_OK);
  const char* value = NULL;
  CHECK(ps_sim_get_choice(sim, "progressive.prolongation", &value) == PS_OK);
  CHECK(value && strcmp(value, "direct") == 0);
  CHECK(ps_sim_get_choice(from_json, "material.bending_model", &value) == PS_OK);
  CHECK(value && strcmp(value, "midedge") == 0);
  double a[75], b[75];
  size_t count = 0;
  for (int round = 0; round < 2; ++round) { /* a preview step on level 0, then level 1 */
    CHECK(ps_sim_step_preview(from_json, 1) == PS_OK);
    CHECK(ps_sim_step_preview(sim, 1) == PS_OK);
    CHECK(ps_sim_refine(from_json) == (round == 0 ? PS_OK : PS_ERROR_OUT_OF_RANGE));
    CHECK(ps_sim_refine(sim) == (round == 0 ? PS_OK : PS_ERROR_OUT_OF_RANGE));
    CHECK(ps_sim_get_positions(from_json, 1, a, 75, &count) == PS_OK && count == 75);
    CHECK(ps_sim_get_positions(sim, 1, b, 75, &count) == PS_OK && count == 75);
    CHECK(memcmp(a, b, sizeof a) == 0); /* bit for bit */
  }
  CHECK(a[3 * 24 + 2] < -1e-3); /* the free edge sags */
  ps_sim_destroy(sim);
  ps_sim_destroy(from_json);
}

static void test_the_mode_picks_the_driver_before_the_first_step(void) {
  ps_sim* json = NULL;
  CHECK(ps_sim_create_from_scene(kScene, NULL, &json) == PS_OK);
  int32_t kind = -1;
  CHECK(ps_sim_get_kind(json, &kind) == PS_OK && kind == PS_SIM_PSQ);
  CHECK(ps_sim_set_choice(json, "simulation.mode", "dynamic") == PS_OK);
  CHECK(ps_sim_get_kind(json, &kind) == PS_OK && kind == PS_SIM_PROGRESSIVE_DYNAMICS);
  CHECK(ps_sim_step_preview(json, 2) == PS_OK);
  int32_t frames = 0;
  CHECK(ps_sim_num_frames(json, 0, &frames) == PS_OK && frames == 3);
  /* After a step the options apply between steps; an animation stays one. */
  CHECK(ps_sim_set_choice(json, "progressive.proxy_hessian", "level") == PS_OK);
  CHECK_ERROR(ps_sim_set_choice(json, "simulation.mode", "quasistatic"), PS_ERROR_INVALID_SCENE,
              ps_sim_last_error(json), "dynamic");
  CHECK(ps_sim_get_kind(json, &kind) == PS_OK && kind == PS_SIM_PROGRESSIVE_DYNAMICS);
  ps_sim_destroy(json);
}

static void test_bad_names_and_values(void) {
  ps_sim* sim = NULL;
  CHECK(ps_sim_create_from_scene(kScene, NULL, &sim) == PS_OK);
  CHECK_ERROR(ps_sim_set_choice(sim, "progressive.proxy_hessian", "exact"),
              PS_ERROR_INVALID_ARGUMENT, ps_sim_last_error(sim),
              "progressive.proxy_hessian: unknown 'exact' (known: auto, level, galerkin)");
  CHECK_ERROR(ps_sim_set_choice(sim, "progressive.smoothing", "on"), PS_ERROR_INVALID_ARGUMENT,
              ps_sim_last_error(sim), "known: simulation.mode, material.bending_model");
  CHECK_ERROR(ps_sim_set_choice(sim, NULL, "on"), PS_ERROR_NULL_ARGUMENT, ps_sim_last_error(sim),
              "name");
  CHECK_ERROR(ps_sim_set_choice(sim, "simulation.mode", NULL), PS_ERROR_NULL_ARGUMENT,
              ps_sim_last_error(sim), "value");
  const char* value = NULL;
  CHECK_ERROR(ps_sim_get_choice(sim, "mode", &value), PS_ERROR_INVALID_ARGUMENT,
              ps_sim_last_error(sim), "unknown option");
  CHECK(ps_sim_get_choice(sim, "progressive.proxy_hessian", &value) == PS_OK);
  CHECK(value && strcmp(value, "galerkin") == 0); /* nothing changed */
  ps_sim_destroy(sim);
}

int main(void) {
  test_the_table_is_listed();
  test_code_equals_json_on_two_levels();
  test_the_mode_picks_the_driver_before_the_first_step();
  test_bad_names_and_values();
  if (failures) fprintf(stderr, "%d check(s) failed\n", failures);
  return failures ? 1 : 0;
}
