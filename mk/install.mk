# make install / make uninstall (docs/install.md). GNU directory variables;
# DESTDIR stages the whole tree (packages, tests/install/test_install.sh):
#   make install PREFIX=/opt/hylo
#   make install DESTDIR=/tmp/stage PREFIX=/usr/local
#   make uninstall (same variables): removes exactly the files install put,
#                  and hylo's own folders when they are left empty
# What goes where:
#   BINDIR      hylo-planner, hylo-scene, hylo-listen, hylo-render,
#               hylo-pngdiff, hylo-cost, hylo-envelope-tightness, hylo-smooth,
#               hylo-trainer (build/bin/trainer)
#   LIBDIR      libhylo.a (the planner), libhylo_lcm.a (LCM types' C code and
#               the message adaptors); static only (docs/install.md says why)
#   INCLUDEDIR  hylo/*.h (the API), hylo/internal/*.h (the workspace's
#               layout, not API), hylo/models/*.h (the committed models),
#               hylo/lcm/*.h (C bindings, hylo_msg.h), hylo/*_t.hpp (C++)
#   DATADIR     hylo/msgs/*.lcm, hylo/python/hylo/ (Python bindings),
#               hylo/params/*.yaml (robot files), hylo/scenes/
#   PKGCONFIGDIR  hylo.pc, hylo-lcm.pc;  CMAKEDIR  hyloConfig*.cmake
PREFIX ?= /usr/local
BINDIR ?= $(PREFIX)/bin
LIBDIR ?= $(PREFIX)/lib
INCLUDEDIR ?= $(PREFIX)/include
DATADIR ?= $(PREFIX)/share
PKGCONFIGDIR ?= $(LIBDIR)/pkgconfig
CMAKEDIR ?= $(LIBDIR)/cmake/hylo
DESTDIR ?=
INSTALL ?= install

# The version: onboard/include/hylo/version.h, the one source of truth.
version_part = $(shell sed -n 's/^\#define HYLO_VERSION_$(1) \([0-9][0-9]*\)$$/\1/p' onboard/include/hylo/version.h)
HYLO_VERSION_MAJOR := $(call version_part,MAJOR)
HYLO_VERSION_MINOR := $(call version_part,MINOR)
HYLO_VERSION_PATCH := $(call version_part,PATCH)
HYLO_VERSION := $(HYLO_VERSION_MAJOR).$(HYLO_VERSION_MINOR).$(HYLO_VERSION_PATCH)

# The LCM types' C code (publish/subscribe) and the adaptors, as the node
# links them.
LCM_LIB := $(BUILD)/lib/libhylo_lcm.a
$(LCM_LIB): $(MSG_OBJS) $(NODE_MSG_OBJS)
	@mkdir -p $(@D)
	rm -f $@ && $(AR) rcs $@ $^
ALL_TARGETS += $(LCM_LIB)

MSG_C_HEADERS := $(MSG_NAMES:%=$(LCM_GEN_DIR)/c/hylo_%.h)
MSG_CPP_HEADERS := $(MSG_NAMES:%=$(LCM_GEN_DIR)/cpp/hylo/%.hpp)
MSG_PYTHON := $(LCM_GEN_DIR)/python/hylo/__init__.py $(MSG_NAMES:%=$(LCM_GEN_DIR)/python/hylo/%.py)
$(MSG_C_HEADERS) $(MSG_CPP_HEADERS) $(MSG_PYTHON): $(LCM_STAMP) ;

# -DHYLO_... given to the build (capacities: the workspace's layout depends
# on them) go to the consumers too, through hylo.pc and hylo::onboard. Give
# make install the CPPFLAGS the library was built with.
HYLO_BUILD_DEFS := $(filter -DHYLO_%,$(CPPFLAGS) $(CFLAGS))

# Install groups: NAME_DIR, NAME_FILES, NAME_MODE. The same lists drive
# install and uninstall, so that uninstall removes exactly what install put.
INSTALL_GROUPS := bin lib include internal models lcm_c lcm_cpp msgs python params scenes pc cmake
bin_DIR := $(BINDIR)
bin_FILES := $(HYLO_PLANNER) $(HYLO_SCENE) $(HYLO_LISTEN) $(HYLO_RENDER) $(HYLO_PNGDIFF) \
	$(HYLO_COST) $(HYLO_ENVELOPE_TIGHTNESS) $(HYLO_SMOOTH)
bin_MODE := 755
lib_DIR := $(LIBDIR)
lib_FILES := $(ONBOARD_LIB) $(LCM_LIB)
include_DIR := $(INCLUDEDIR)/hylo
include_FILES := $(ONBOARD_PUBLIC_HEADERS)
internal_DIR := $(INCLUDEDIR)/hylo/internal
internal_FILES := $(ONBOARD_INTERNAL_HEADERS)
models_DIR := $(INCLUDEDIR)/hylo/models
models_FILES := $(MODEL_HEADERS)
lcm_c_DIR := $(INCLUDEDIR)/hylo/lcm
lcm_c_FILES := $(MSG_C_HEADERS) onboard/msg/hylo_msg.h
lcm_cpp_DIR := $(INCLUDEDIR)/hylo
lcm_cpp_FILES := $(MSG_CPP_HEADERS)
msgs_DIR := $(DATADIR)/hylo/msgs
msgs_FILES := $(MSG_FILES)
python_DIR := $(DATADIR)/hylo/python/hylo
python_FILES := $(MSG_PYTHON)
params_DIR := $(DATADIR)/hylo/params
params_FILES := $(sort $(wildcard trainer/params/*.yaml))
scenes_DIR := $(DATADIR)/hylo/scenes
scenes_FILES := $(sort $(wildcard scenes/*.yaml scenes/*.pgm scenes/README.md))
INSTALL_GEN := $(BUILD)/install
pc_DIR := $(PKGCONFIGDIR)
pc_FILES := $(INSTALL_GEN)/hylo.pc $(INSTALL_GEN)/hylo-lcm.pc
cmake_DIR := $(CMAKEDIR)
cmake_FILES := $(INSTALL_GEN)/hyloConfig.cmake $(INSTALL_GEN)/hyloConfigVersion.cmake
# The trainer is installed under a name of its own.
TRAINER_INSTALLED := $(BINDIR)/hylo-trainer
# hylo's own folders, deepest first: uninstall removes them when empty.
INSTALL_OWN_DIRS := $(INCLUDEDIR)/hylo/internal $(INCLUDEDIR)/hylo/models $(INCLUDEDIR)/hylo/lcm \
	$(INCLUDEDIR)/hylo $(DATADIR)/hylo/msgs $(DATADIR)/hylo/python/hylo $(DATADIR)/hylo/python \
	$(DATADIR)/hylo/params $(DATADIR)/hylo/scenes $(DATADIR)/hylo $(CMAKEDIR)

empty :=
space := $(empty) $(empty)
# A folder of DIR in pkg-config's terms: ${prefix}/... inside PREFIX.
pc_path = $(if $(filter $(PREFIX)/%,$(1)),$${prefix}/$(patsubst $(PREFIX)/%,%,$(1)),$(1))
# The relative path from CMAKEDIR to DIR (the CMake package is relocatable).
cmake_rel = $(shell realpath -m --relative-to='$(CMAKEDIR)' '$(1)')
POINTER_BYTES = $(or $(shell printf '__SIZEOF_POINTER__\n' | $(CC) -E -P -x c - 2>/dev/null | tr -d ' '),8)
INSTALL_SED = sed -e 's|@PREFIX@|$(PREFIX)|g' -e 's|@PC_LIBDIR@|$(call pc_path,$(LIBDIR))|g' \
	-e 's|@PC_INCLUDEDIR@|$(call pc_path,$(INCLUDEDIR))|g' -e 's|@PC_DATADIR@|$(call pc_path,$(DATADIR))|g' \
	-e 's|@DEFS@|$(if $(HYLO_BUILD_DEFS),$(space)$(HYLO_BUILD_DEFS))|g' \
	-e 's|@CMAKE_REL_LIBDIR@|$(call cmake_rel,$(LIBDIR))|g' \
	-e 's|@CMAKE_REL_INCLUDEDIR@|$(call cmake_rel,$(INCLUDEDIR))|g' \
	-e 's|@CMAKE_REL_DATADIR@|$(call cmake_rel,$(DATADIR))|g' \
	-e 's|@CMAKE_DEFS@|$(subst $(space),;,$(strip $(HYLO_BUILD_DEFS:-D%=%)))|g' \
	-e 's|@VERSION@|$(HYLO_VERSION)|g' -e 's|@MAJOR@|$(HYLO_VERSION_MAJOR)|g' \
	-e 's|@MINOR@|$(HYLO_VERSION_MINOR)|g' -e 's|@POINTER_BYTES@|$(POINTER_BYTES)|g' \
	-e 's|@POINTER_BITS@|$(shell echo $$(($(POINTER_BYTES) * 8)))|g'
# One line per group: $(call install_group,NAME)
define install_group
	$(INSTALL) -d '$(DESTDIR)$($(1)_DIR)'
	$(INSTALL) -m $(or $($(1)_MODE),644) $($(1)_FILES) '$(DESTDIR)$($(1)_DIR)/'

endef
define uninstall_group
	rm -f $(foreach f,$(notdir $($(1)_FILES)),'$(DESTDIR)$($(1)_DIR)/$(f)')

endef

# Every file install copies, built first (only these: make install does not
# build the tests).
INSTALL_BUILT := $(filter $(BUILD)/%,$(foreach g,$(filter-out pc cmake,$(INSTALL_GROUPS)),$($(g)_FILES))) $(TRAINER)

.PHONY: install uninstall install-gen
install-gen: tools/install/hylo.pc.in tools/install/hylo-lcm.pc.in tools/install/hyloConfig.cmake.in \
		tools/install/hyloConfigVersion.cmake.in
	@mkdir -p $(INSTALL_GEN)
	@test -n '$(HYLO_VERSION_MAJOR)' -a -n '$(HYLO_VERSION_MINOR)' -a -n '$(HYLO_VERSION_PATCH)' || \
		{ echo "install: no version in onboard/include/hylo/version.h" >&2; exit 1; }
	@for f in hylo.pc hylo-lcm.pc hyloConfig.cmake hyloConfigVersion.cmake; do \
		$(INSTALL_SED) tools/install/$$f.in > $(INSTALL_GEN)/$$f || exit 1; done

install: $(INSTALL_BUILT) install-gen
	$(foreach g,$(INSTALL_GROUPS),$(call install_group,$(g)))
	$(INSTALL) -m 755 $(TRAINER) '$(DESTDIR)$(TRAINER_INSTALLED)'

uninstall:
	$(foreach g,$(INSTALL_GROUPS),$(call uninstall_group,$(g)))
	rm -f '$(DESTDIR)$(TRAINER_INSTALLED)'
	@for d in $(INSTALL_OWN_DIRS); do \
		if [ -d "$(DESTDIR)$$d" ]; then rmdir "$(DESTDIR)$$d" 2>/dev/null || \
			echo "uninstall: $(DESTDIR)$$d is not empty: kept"; fi; done

# Test: install into a stage, build out-of-tree consumers with pkg-config and
# CMake against it, uninstall (tests/install/test_install.sh; needs cmake).
tests/install/test_install.sh: $(INSTALL_BUILT) $(NATIVE_DIGEST)
TESTS += tests/install/test_install.sh
