# Two commands do all set-up on a fresh Debian 12 machine:
#   make run   installs missing packages, builds, renders the default scene to out/default/
#   make test  installs missing packages, builds, runs every test through CTest
BUILD ?= build
JOBS ?= $(shell nproc)
PACKAGES := build-essential cmake pkg-config nlohmann-json3-dev catch2 \
            libosmesa6-dev libstb-dev zlib1g-dev libglfw3-dev xvfb xauth xdotool
SUDO := $(shell [ "$$(id -u)" -eq 0 ] || echo sudo)

.PHONY: deps build run test clean

deps:
	@missing=""; for p in $(PACKAGES); do \
	  dpkg-query -W -f='$${Status}' $$p 2>/dev/null | grep -q 'install ok installed' || missing="$$missing $$p"; \
	done; \
	if [ -n "$$missing" ]; then \
	  echo "installing:$$missing"; \
	  $(SUDO) apt-get update -qq && \
	  DEBIAN_FRONTEND=noninteractive $(SUDO) apt-get install -y -qq --no-install-recommends $$missing; \
	fi

build: deps
	cmake -S . -B $(BUILD) -DCMAKE_BUILD_TYPE=Release
	cmake --build $(BUILD) -j $(JOBS)

run: build
	./$(BUILD)/ballbox render

test: build
	cd $(BUILD) && ctest --output-on-failure -j $(JOBS)

clean:
	rm -rf $(BUILD)
