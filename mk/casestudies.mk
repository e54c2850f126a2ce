# The paper's case studies (tools/casestudies/): build/bin/hylo-casestudies
# runs them and writes docs/results.{md,json}; plot.py draws the figures;
# docs/provenance.json records the models and scenes they were made from.
#   make casestudies         every study (see docs/casestudies.md for how long)
#   make casestudies QUICK=1 the DI convergence on 3 spacings (a check)
HYLO_CASESTUDIES := $(BUILD)/bin/hylo-casestudies

CHASM_OBJ := $(BUILD)/obj/tools/casestudies/chasm.o

$(CHASM_OBJ): tools/casestudies/chasm.cpp
	@mkdir -p $(@D)
	$(CXX) $(TRAINER_CFLAGS) -c $< -o $@

# The Drivocopter study's solve log is keyed by a hash of the sources its
# solves depend on (the trainer, the planning library, the models, the
# study), so a rerun never takes a record made by other code.
CASESTUDY_SOURCES := $(sort $(wildcard trainer/*.cpp trainer/*.hpp onboard/src/*.c onboard/src/*.h \
	onboard/include/hylo/*.h onboard/models/*.h tools/casestudies/*.cpp tools/casestudies/*.hpp))
CASESTUDY_SOURCES_SHA = $(shell cat $(CASESTUDY_SOURCES) | sha256sum | cut -c1-16)
$(HYLO_CASESTUDIES): tools/casestudies/casestudies.cpp trainer/cli.hpp $(CHASM_OBJ) tools/scene/planner_view.hpp $(BUILD)/obj/tools/scene/scene.o \
		$(BUILD)/obj/node/registry.o $(BUILD)/obj/node/registry_models.o $(TRAINER_LIB) $(ONBOARD_LIB) $(CASESTUDY_SOURCES)
	@mkdir -p $(@D)
	$(CXX) $(TRAINER_CFLAGS) $(LDFLAGS) $(NODE_INC) -DHYLO_SOURCES_SHA='"$(CASESTUDY_SOURCES_SHA)"' $< $(filter %.o %.a,$^) $(TRAINER_LIBS) -lm -o $@

ALL_TARGETS += $(HYLO_CASESTUDIES)

# Test: the chasm scenes and the fixed sequences' plans (C++, TAP).
CHASM_TEST := $(BUILD)/test/casestudies/test_chasm
$(CHASM_TEST): tests/casestudies/test_chasm.cpp $(CHASM_OBJ) $(BUILD)/obj/tools/scene/scene.o $(TRAINER_LIB)
	@mkdir -p $(@D)
	$(CXX) $(TRAINER_CFLAGS) $(LDFLAGS) $< $(filter %.o %.a,$^) $(TRAINER_LIBS) -o $@
ALL_TARGETS += $(CHASM_TEST)
TESTS += $(CHASM_TEST)

# Figures need matplotlib (PyPI, into .venv).
venv-report: .venv/.report-stamp
.venv/.report-stamp: .venv/.stamp tools/requirements-report.txt
	.venv/bin/pip install -q -r tools/requirements-report.txt
	@touch $@

casestudies: deps
	@$(MAKE) --no-print-directory all venv-report
	@mkdir -p docs/results
	$(HYLO_CASESTUDIES) --out docs $(if $(QUICK),--quick)
	.venv/bin/python tools/casestudies/plot.py docs/results.json docs/results
	tools/provenance record docs/results.md docs/results.json docs/results/*

# Test: the command line and the quick Ambot study (tests/casestudies/).
tests/casestudies/test_casestudies.sh: $(HYLO_CASESTUDIES)
TESTS += tests/casestudies/test_casestudies.sh
