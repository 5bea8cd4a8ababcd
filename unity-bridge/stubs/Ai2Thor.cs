// STUB, not AI2-THOR: the members of AI2-THOR's Unity project (unity/Assets/Scripts, compiled into
// Assembly-CSharp) that the sample adapter calls. AgentManager.ProcessControlCommand(DynamicServerAction)
// is the entry point AI2-THOR's own servers use; CreateHouse, TeleportFull, OpenObject... are actions
// dispatched through it. Agreement with this file proves agreement with this file only.
using System.Collections.Generic;
using UnityEngine;
using UnityStandardAssets.Characters.FirstPerson;

public enum AgentState { Processing, ActionComplete, PendingFixedUpdate, Error, Emit }

public class DynamicServerAction
{
    public DynamicServerAction(Dictionary<string, object> action) { }
    public string action { get { return null; } }
}

public enum SimObjType { Undefined = 0, Apple, Bread, Fridge, Microwave, CounterTop, Knife }

public class SimObjPhysics : MonoBehaviour
{
    public string ObjectID { get; set; }
    public SimObjType Type { get { return SimObjType.Undefined; } }
}

public class AgentManager : MonoBehaviour
{
    public BaseFPSAgentController PrimaryAgent { get { return null; } }
    public void ProcessControlCommand(DynamicServerAction controlCommand) { }
}

namespace UnityStandardAssets.Characters.FirstPerson
{
    public abstract class BaseFPSAgentController
    {
        public bool lastActionSuccess;
        public string errorMessage;
        public AgentState agentState;
        public object actionReturn;
    }
}
