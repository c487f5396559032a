package painleve.importers;

import java.io.File;
import java.io.PrintStream;

import no.ntnu.ihb.fmi4j.FmiStatus;
import no.ntnu.ihb.fmi4j.importer.fmi2.Fmu;
import no.ntnu.ihb.fmi4j.importer.fmi2.ModelExchangeInstance;
import no.ntnu.ihb.fmi4j.importer.fmi2.jni.EventInfo;

/**
 * Runs PainleveRod.fmu through FMI 2.0 Model Exchange with FMI4j's instance and a
 * fixed-step forward Euler master, the method of fmpy's solver="Euler" step for step
 * (FMI4j 0.38.0 on Maven Central ships no integrator of its own), and prints the
 * outputs after every step as CSV.
 *
 * Usage: ModelExchangeEuler FMU STOP_TIME STEPS
 *
 * Each step: x += (t_next - t) der(x) with t_next = (n + 1) h, then the event
 * indicators; a sign change against the previous step's indicators (fmpy's rule: from
 * below to >= 0 or from above to <= 0) is a state event, handled at the step's end
 * (enterEventMode, newDiscreteStates until the FMU is done, enterContinuousTimeMode).
 * No start value is set: the default experiment.
 */
public final class ModelExchangeEuler {

    private ModelExchangeEuler() {
    }

    static void check(FmiStatus status, String call) {
        if (status != FmiStatus.OK) {
            CoSimulate.fail("fmi4j: " + call + " returned " + status);
        }
    }

    static void eventIteration(ModelExchangeInstance fmu) {
        EventInfo info = fmu.getEventInfo$fmi_import();
        do {
            check(fmu.newDiscreteStates(), "fmi2NewDiscreteStates");
            if (info.getTerminateSimulation()) {
                CoSimulate.fail("fmi4j: the FMU asked to terminate");
            }
        } while (info.getNewDiscreteStatesNeeded());
    }

    public static void main(String[] args) throws Exception {
        if (args.length != 3) {
            System.err.println("usage: ModelExchangeEuler FMU STOP_TIME STEPS");
            System.exit(2);
        }
        File file = new File(args[0]);
        double stop = Double.parseDouble(args[1]);
        int steps = Integer.parseInt(args[2]);
        double h = stop / steps;
        CoSimulate.readValueReferences(file);
        PrintStream out = System.out;
        out.println("time," + String.join(",", CoSimulate.REALS) + ",mode,contact");

        Fmu fmu = Fmu.from(file);
        try (ModelExchangeInstance instance = fmu.asModelExchangeFmu().newInstance("rod")) {
            int nx = instance.getModelDescription().getNumberOfContinuousStates();
            int nz = instance.getModelDescription().getNumberOfEventIndicators();
            double[] x = new double[nx];
            double[] dx = new double[nx];
            double[] z = new double[nz];
            double[] previous = new double[nz];
            double[] reals = new double[CoSimulate.REALS.length];
            int[] mode = new int[1];
            boolean[] contact = new boolean[1];

            // start 0, stop time, no tolerance (Model Exchange: the master's method decides)
            if (!instance.setupExperiment(0.0, stop, 0.0) || !instance.enterInitializationMode()
                    || !instance.exitInitializationMode()) {
                CoSimulate.fail("fmi4j: initialization failed: " + instance.getLastStatus());
            }
            eventIteration(instance);
            check(instance.enterContinuousTimeMode(), "fmi2EnterContinuousTimeMode");
            check(instance.getEventIndicators(z), "fmi2GetEventIndicators");

            double t = 0.0;
            for (int n = 0; ; n++) {
                check(instance.readReal(CoSimulate.REAL_VRS, reals), "fmi2GetReal");
                check(instance.readInteger(CoSimulate.MODE_VR, mode), "fmi2GetInteger");
                check(instance.readBoolean(CoSimulate.CONTACT_VR, contact), "fmi2GetBoolean");
                CoSimulate.row(out, t, reals, mode[0], contact[0]);
                if (n == steps) {
                    break;
                }
                double next = (n + 1) * h;
                check(instance.getContinuousStates(x), "fmi2GetContinuousStates");
                check(instance.getDerivatives(dx), "fmi2GetDerivatives");
                for (int i = 0; i < nx; i++) {
                    x[i] += (next - t) * dx[i];
                }
                check(instance.setContinuousStates(x), "fmi2SetContinuousStates");
                System.arraycopy(z, 0, previous, 0, nz);
                check(instance.getEventIndicators(z), "fmi2GetEventIndicators");
                boolean stateEvent = false;
                for (int i = 0; i < nz; i++) {
                    stateEvent |= (previous[i] < 0 && z[i] >= 0) || (previous[i] > 0 && z[i] <= 0);
                }
                t = next;
                check(instance.setTime(t), "fmi2SetTime");
                boolean stepEvent = instance.completedIntegratorStep().getEnterEventMode();
                if (stateEvent || stepEvent) {
                    check(instance.enterEventMode(), "fmi2EnterEventMode");
                    eventIteration(instance);
                    check(instance.enterContinuousTimeMode(), "fmi2EnterContinuousTimeMode");
                }
            }
            instance.terminate();
        } finally {
            fmu.close();
        }
        out.flush();
    }
}
