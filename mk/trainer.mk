# Trainer (C++17): robot parameter files, dynamics, Hermite-Simpson
# collocation with Ipopt, CVODE replay, datasets, SVR fit and export.
#   build/bin/trainer
TRAINER_SRCS := trainer/params.cpp trainer/robot_params.cpp trainer/collocation.cpp trainer/hand_overs.cpp trainer/ipopt_nlp.cpp trainer/mode_config.cpp trainer/modes.cpp \
	trainer/solve_strategy.cpp trainer/starts.cpp trainer/replay.cpp \
	trainer/dataset.cpp trainer/svr_fit.cpp trainer/svr_export.cpp trainer/envelope.cpp trainer/sha256.cpp \
	trainer/pipeline.cpp trainer/switching.cpp trainer/smoother.cpp trainer/smoothing_problem.cpp trainer/map_guards.cpp \
	trainer/fallbacks.cpp trainer/domain_check.cpp trainer/smooth_alternatives.cpp trainer/processes.cpp \
	trainer/numerics.cpp trainer/memory.cpp trainer/frame.cpp trainer/repair.cpp trainer/gather.cpp trainer/clearance.cpp trainer/files.cpp trainer/corridor.cpp
TRAINER_OBJS := $(TRAINER_SRCS:%.cpp=$(BUILD)/obj/%.o)
TRAINER_CFLAGS := $(CXX17_FLAGS) $(DEP_FLAGS) -I. -Ionboard/include $(IPOPT_CFLAGS) $(EIGEN_CFLAGS) $(YAML_CFLAGS)
TRAINER_LIBS := $(IPOPT_LIBS) $(SUNDIALS_LIBS) $(YAML_LIBS) $(SVM_LIBS) -lpthread
TRAINER_LIB := $(BUILD)/lib/libhylo_trainer.a
TRAINER := $(BUILD)/bin/trainer

$(BUILD)/obj/trainer/%.o: trainer/%.cpp
	@mkdir -p $(@D)
	$(CXX) $(TRAINER_CFLAGS) -c $< -o $@

# The trainer computes features, the envelope's costs and clearances with
# the onboard code itself.
TRAINER_ONBOARD_OBJS := $(addprefix $(BUILD)/obj/onboard/src/,features.o svr.o envelope.o status.o region.o types.o \
	modes.o clearance.o map.o)
$(TRAINER_LIB): $(TRAINER_OBJS) $(TRAINER_ONBOARD_OBJS)
	@mkdir -p $(@D)
	rm -f $@ && $(AR) rcs $@ $^

$(TRAINER): $(BUILD)/obj/trainer/main.o $(TRAINER_LIB)
	@mkdir -p $(@D)
	$(CXX) $(CXXFLAGS) $(LDFLAGS) $^ $(TRAINER_LIBS) -o $@

ALL_TARGETS += $(TRAINER)

# Tests: the numerics (C++, TAP) and the CLI and datasets (shell, TAP).
TRAINER_TEST := $(BUILD)/test/trainer/test_collocation
$(TRAINER_TEST): tests/trainer/test_collocation.cpp $(TRAINER_LIB)
	@mkdir -p $(@D)
	$(CXX) $(TRAINER_CFLAGS) $(LDFLAGS) $< $(TRAINER_LIB) $(TRAINER_LIBS) -o $@
MULTIPHASE_TEST := $(BUILD)/test/trainer/test_multiphase
$(MULTIPHASE_TEST): tests/trainer/test_multiphase.cpp $(TRAINER_LIB)
	@mkdir -p $(@D)
	$(CXX) $(TRAINER_CFLAGS) $(LDFLAGS) $< $(TRAINER_LIB) $(TRAINER_LIBS) -o $@
RELABEL_TEST := $(BUILD)/test/trainer/test_relabel
$(RELABEL_TEST): tests/trainer/test_relabel.cpp $(TRAINER_LIB)
	@mkdir -p $(@D)
	$(CXX) $(TRAINER_CFLAGS) $(LDFLAGS) $< $(TRAINER_LIB) $(TRAINER_LIBS) -o $@
DRAWS_TEST := $(BUILD)/test/trainer/test_draws
$(DRAWS_TEST): tests/trainer/test_draws.cpp $(TRAINER_LIB)
	@mkdir -p $(@D)
	$(CXX) $(TRAINER_CFLAGS) $(LDFLAGS) $< $(TRAINER_LIB) $(TRAINER_LIBS) -o $@
PROCESSES_TEST := $(BUILD)/test/trainer/test_processes
$(PROCESSES_TEST): tests/trainer/test_processes.cpp $(TRAINER_LIB)
	@mkdir -p $(@D)
	$(CXX) $(TRAINER_CFLAGS) $(LDFLAGS) $< $(TRAINER_LIB) $(TRAINER_LIBS) -o $@
REPAIR_TEST := $(BUILD)/test/trainer/test_repair
$(REPAIR_TEST): tests/trainer/test_repair.cpp $(TRAINER_LIB)
	@mkdir -p $(@D)
	$(CXX) $(TRAINER_CFLAGS) $(LDFLAGS) $< $(TRAINER_LIB) $(TRAINER_LIBS) -o $@
MEMORY_TEST := $(BUILD)/test/trainer/test_memory
$(MEMORY_TEST): tests/trainer/test_memory.cpp $(TRAINER_LIB)
	@mkdir -p $(@D)
	$(CXX) $(TRAINER_CFLAGS) $(LDFLAGS) $< $(TRAINER_LIB) $(TRAINER_LIBS) -o $@
CLEARANCE_CHECK_TEST := $(BUILD)/test/trainer/test_clearance_check
$(CLEARANCE_CHECK_TEST): tests/trainer/test_clearance_check.cpp $(TRAINER_LIB)
	@mkdir -p $(@D)
	$(CXX) $(TRAINER_CFLAGS) $(LDFLAGS) $< $(TRAINER_LIB) $(TRAINER_LIBS) -o $@
CORRIDOR_TEST := $(BUILD)/test/trainer/test_corridor
$(CORRIDOR_TEST): tests/trainer/test_corridor.cpp $(TRAINER_LIB)
	@mkdir -p $(@D)
	$(CXX) $(TRAINER_CFLAGS) $(LDFLAGS) $< $(TRAINER_LIB) $(TRAINER_LIBS) -o $@
WALL_CROSSINGS_TEST := $(BUILD)/test/trainer/test_wall_crossings
$(WALL_CROSSINGS_TEST): tests/trainer/test_wall_crossings.cpp $(TRAINER_LIB)
	@mkdir -p $(@D)
	$(CXX) $(TRAINER_CFLAGS) $(LDFLAGS) $< $(TRAINER_LIB) $(TRAINER_LIBS) -o $@
tests/trainer/test_trainer_cli.sh: $(TRAINER)
tests/trainer/test_solve_memory.sh: $(TRAINER)
# Labels independent of the CPU (trainer/numerics.hpp): runs the trainer and
# test_collocation under several OpenBLAS kernel settings and hwcaps masks.
tests/trainer/test_numerics.sh: $(TRAINER) $(TRAINER_TEST)
ALL_TARGETS += $(TRAINER_TEST) $(MULTIPHASE_TEST) $(RELABEL_TEST) $(DRAWS_TEST) $(PROCESSES_TEST) $(REPAIR_TEST) $(MEMORY_TEST) $(CLEARANCE_CHECK_TEST) $(CORRIDOR_TEST) \
	$(WALL_CROSSINGS_TEST)
TESTS += $(TRAINER_TEST) $(MULTIPHASE_TEST) $(RELABEL_TEST) $(DRAWS_TEST) $(PROCESSES_TEST) $(REPAIR_TEST) $(MEMORY_TEST) $(CLEARANCE_CHECK_TEST) $(CORRIDOR_TEST) \
	$(WALL_CROSSINGS_TEST) tests/trainer/test_trainer_cli.sh tests/trainer/test_solve_memory.sh \
	tests/trainer/test_numerics.sh

# make models: regenerates every committed model (datasets resume; see
# docs/cost-models.md for the time it takes). MODEL_SAMPLES= overrides the sample counts.
MODEL_JOBS ?= $(shell nproc)
MODEL_LIST := di:di_neg di:di_pos ambot:ground ambot:marine drivocopter:ground drivocopter:flight
models: deps $(TRAINER)
	@for rm in $(MODEL_LIST); do \
		r=$${rm%%:*}; m=$${rm##*:}; \
		echo "== $$r $$m"; \
		$(TRAINER) --robot $$r --mode $$m --jobs $(MODEL_JOBS) --out trainer/datasets/$$r \
			$(if $(MODEL_SAMPLES),--samples $(MODEL_SAMPLES)) || exit 1; \
	done
	@$(MAKE) --no-print-directory model-pictures

# make regenerate MODEL=robot:mode: one model's data made again as the
# committed ones are to be (docs/trainer.md, "Regenerating a model"): a new
# dataset in build/regen/<robot> (the pinned numerics, the newest draw, every
# start refined), repaired from 8 neighbours' solutions, fitted (with the
# committed header's errors on the same held-out rows) and exported into
# build/regen/models. Resumable: run it again after an interruption.
REGEN_DIR ?= $(BUILD)/regen
regenerate: deps $(TRAINER)
	@case " $(MODEL_LIST) " in *" $(MODEL) "*) ;; \
	  *) echo "make regenerate: MODEL=robot:mode, one of: $(MODEL_LIST)" >&2; exit 2 ;; esac
	@r=$(firstword $(subst :, ,$(MODEL))); m=$(lastword $(subst :, ,$(MODEL))); \
	set -e; mkdir -p $(REGEN_DIR)/models; \
	for stage in gen repair fit export; do \
		echo "== $$r $$m: $$stage"; \
		$(TRAINER) --robot $$r --mode $$m --stage $$stage --refine-within inf --neighbours 8 --solutions \
			--jobs $(MODEL_JOBS) --out $(REGEN_DIR)/$$r --models-dir $(REGEN_DIR)/models \
			$(if $(MODEL_SAMPLES),--samples $(MODEL_SAMPLES)) \
			$$(if [ $$stage = fit ] && [ -f onboard/models/$${r}_$$m.h ]; then echo --compare onboard/models/$${r}_$$m.h; fi); \
	done
.PHONY: regenerate

# Pictures of the committed models (tools/models/plot_models.py, matplotlib
# from PyPI): training trajectories and the learned cost, into docs/models/.
MODEL_PICTURES := ambot:ground ambot:marine drivocopter:ground drivocopter:flight
model-pictures: venv-report $(TRAINER) $(BUILD)/bin/hylo-cost
	@for rm in $(MODEL_PICTURES); do \
		.venv/bin/python tools/models/plot_models.py $${rm%%:*} $${rm##*:} docs/models || exit 1; \
		tools/provenance record docs/models/$${rm%%:*}_$${rm##*:}_*.png || exit 1; \
	done

# Trainer solve-time benchmark (tools/bench/bench_trainer.cpp).
BENCH_TRAINER := $(BUILD)/bench/bin/bench_trainer
$(BENCH_TRAINER): tools/bench/bench_trainer.cpp tools/bench/results.hpp $(TRAINER_LIB)
	@mkdir -p $(@D)
	$(CXX) $(TRAINER_CFLAGS) $(LDFLAGS) $< $(TRAINER_LIB) $(TRAINER_LIBS) -o $@
BENCH_TARGETS += $(BENCH_TRAINER)

# hylo-smooth: the final path smoothing node (trainer/smooth_main.cpp).
HYLO_SMOOTH := $(BUILD)/bin/hylo-smooth
$(BUILD)/obj/trainer/smooth_main.o: trainer/smooth_main.cpp $(LCM_STAMP)
	@mkdir -p $(@D)
	$(CXX) $(TRAINER_CFLAGS) -isystem $(LCM_GEN_DIR)/cpp -c $< -o $@
$(HYLO_SMOOTH): $(BUILD)/obj/trainer/smooth_main.o $(TRAINER_LIB)
	@mkdir -p $(@D)
	$(CXX) $(CXXFLAGS) $(LDFLAGS) $^ $(TRAINER_LIBS) $(LCM_LIBS) -o $@
ALL_TARGETS += $(HYLO_SMOOTH)
tests/trainer/test_smooth.sh: $(HYLO_SMOOTH) $(TRAINER)
TESTS += tests/trainer/test_smooth.sh
tests/trainer/test_alternatives.sh: $(HYLO_SMOOTH) $(TRAINER) $(BUILD)/bin/hylo-scene $(BUILD)/bin/hylo-planner $(BUILD)/bin/hylo-listen
TESTS += tests/trainer/test_alternatives.sh
tests/trainer/test_fallback.sh: $(HYLO_SMOOTH) $(BUILD)/bin/hylo-scene $(BUILD)/bin/hylo-planner $(BUILD)/bin/hylo-listen
TESTS += tests/trainer/test_fallback.sh
# The committed Ambot scenes' trajectories, walked from outside (tools/clearance_walk.py).
tests/trainer/test_clearance_scenes.sh: $(HYLO_SMOOTH) $(BUILD)/bin/hylo-scene $(BUILD)/bin/hylo-planner tools/clearance_walk.py
TESTS += tests/trainer/test_clearance_scenes.sh
# No component cycle among the trainer's files (#include "trainer/...").
TESTS += tests/trainer/test_components.sh
