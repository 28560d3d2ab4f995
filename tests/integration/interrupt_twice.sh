#!/bin/sh
# interrupt_twice.sh DELAY PROGRAM [ARGS...]: runs PROGRAM, sends it SIGINT after 2 s and again
# DELAY seconds later, and exits with its status. Used to check that one request to stop, delivered
# twice (as `timeout -s INT` and a signal to a process group do), is taken as one.
delay=$1
shift
"$@" &
pid=$!
sleep 2
kill -INT "$pid"
sleep "$delay"
kill -INT "$pid" 2>/dev/null
wait "$pid"
